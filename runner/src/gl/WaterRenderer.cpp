// The water renderer's GL side. A frame is planned on the CPU first (matrices, the water polygon,
// clip planes, which meshes each pass draws), then executed with GL calls only, so the harness's
// own cost per frame can be measured apart from the driver's.
#include "tidepool/TextFile.h"
#include "tidepool/runner/FramePlan.h"
#include "tidepool/runner/MesaInfoLog.h"
#include "tidepool/runner/Renderer.h"
#include "tidepool/runner/ShaderFeatures.h"
#include "tidepool/runner/WaterMath.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "gl/GlApi.h"
#include "gl/GlContextImpl.h"
#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

namespace tidepool::runner {
namespace {

// Attribute locations bound before linking, the same for every program.
constexpr GLuint kAttribVertex = 0;
constexpr GLuint kAttribNormal = 1;
constexpr GLuint kAttribColour = 2;
constexpr GLuint kAttribFourier0 = 3;  // REFLECTION_FOURIER coefficients (a0, a1, b1, a2)
constexpr GLuint kAttribFourier1 = 4;  // and (b2, a3, b3, a4)

// A vertex attribute's byte offset into the bound buffer, which GL takes as a pointer.
const void* BufferOffset(std::size_t bytes) {
    // glVertexAttribPointer takes the offset as a pointer; an integer cast is the only way.
    return reinterpret_cast<const void*>(bytes);  // NOLINT(performance-no-int-to-ptr)
}

// Texture units.
constexpr GLint kUnitReflection = 0;
constexpr GLint kUnitRefraction = 1;
constexpr GLint kUnitNormalMap = 2;
constexpr GLint kUnitNormalisation = 3;
constexpr GLint kUnitSky = 4;
constexpr GLint kUnitLowRes = 5;

std::string ErrorName(GLenum error) {
    switch (error) {
        case GL_INVALID_ENUM:
            return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE:
            return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION:
            return "GL_INVALID_OPERATION";
        case GL_OUT_OF_MEMORY:
            return "GL_OUT_OF_MEMORY";
        case GL_INVALID_FRAMEBUFFER_OPERATION:
            return "GL_INVALID_FRAMEBUFFER_OPERATION";
        default:
            return fmt::format("GL error 0x{:x}", error);
    }
}

std::string ReadText(const std::filesystem::path& path, bool* ok) {
    TextFileRead read = ReadShaderFile(path);
    *ok = read.ok;
    return std::move(read.text);
}

// The colour REFLECTION_FOURIER gives reflected terrain: the mean of the terrain's vertex
// colours above the water, lit as model.vsh lights them (albedo * (0.35 + 0.65 max(N.L, 0))).
// Black when no terrain vertex lies above the water.
glm::vec3 MeanLitColourAbove(const Mesh& terrain, float water_height, glm::vec3 sun_direction) {
    const glm::mat3 rotation(terrain.model_matrix);
    glm::dvec3 sum(0.0);
    std::size_t count = 0;
    for (std::size_t i = 0; i < terrain.positions.size(); ++i) {
        const glm::vec3 world =
                glm::vec3(terrain.model_matrix * glm::vec4(terrain.positions[i], 1));
        if (world.y <= water_height) {
            continue;
        }
        const glm::vec3 normal = glm::normalize(rotation * terrain.normals[i]);
        const float light = 0.35F + 0.65F * std::max(glm::dot(normal, sun_direction), 0.0F);
        sum += glm::dvec3(terrain.colours[i] * light);
        ++count;
    }
    return count == 0 ? glm::vec3(0.0F) : glm::vec3(sum / static_cast<double>(count));
}

struct MeshBuffers {
    GLuint vertices = 0;
    GLuint indices = 0;
    GLsizei index_count = 0;
};

struct CompiledProgram {
    bool valid = false;
    GLuint id = 0;
    std::map<std::string, GLint, std::less<>> uniforms;
    DriverVerdict verdict;
};

struct RenderTarget {
    GLuint framebuffer = 0;
    GLuint colour = 0;  // texture
    GLuint depth = 0;   // renderbuffer, 0 when none
    int width = 0;
    int height = 0;
};

}  // namespace

struct WaterRenderer::Impl {
    GlContext* context = nullptr;
    const gl::GlApi* gl = nullptr;
    const gl::GlTimerQueryApi* timer_query = nullptr;
    GLuint gpu_query = 0;  // the GPU timer query, made on first use
    bool gpu_query_running = false;
    VariantConfig config;
    RenderSettings settings;
    Scene scene;
    bool scene_given = false;  // Create received a scene; Init keeps it instead of the default

    std::vector<MeshBuffers> meshes;  // terrain first, then scene.objects
    MeshBuffers sky_cube;
    GLuint water_vertices = 0;
    // REFLECTION_FOURIER: the tessellated water grid with per-vertex coefficients, built on the
    // first Prepare of a Fourier configuration (it costs a heightfield march per vertex).
    MeshBuffers fourier_grid;
    bool fourier_grid_built = false;
    std::string fourier_grid_error;
    glm::vec3 terrain_reflection_colour{0.0F};
    GLuint sky_texture = 0;
    GLuint normal_map = 0;
    GLuint normalisation_cube = 0;

    RenderTarget main;
    RenderTarget low_res;
    // Reflection and refraction targets per size, kept so that interleaved configurations with
    // different sizes never reallocate inside a timed frame.
    std::map<int, RenderTarget> reflection_targets;
    std::map<int, RenderTarget> refraction_targets;
    RenderTarget reflection;  // the current frame's targets (copies of handles in the maps)
    RenderTarget refraction;

    std::map<std::string, CompiledProgram> programs;  // by program id (variant id or helper id)
    std::map<std::string, std::string> sources;       // shader file contents by path

    ~Impl();
    std::string Init();
    GLuint UploadCube(const CubeMapImage& image);
    MeshBuffers UploadMesh(const Mesh& mesh);
    std::string MakeTarget(RenderTarget* target, int width, int height, GLenum internal_format,
                           GLenum type, bool with_depth);
    void FreeTarget(RenderTarget* target);
    CompiledProgram& Program(const Variant& variant);
    GLint Uniform(CompiledProgram& program, const char* name);
    std::string EnsureTarget(std::map<int, RenderTarget>* targets, int size);
    void DrawSky(const PassPlan& pass, FrameReport* report);
    void DrawModels(const PassPlan& pass, FrameReport* report);
    void DrawWater(const FramePlan& plan, const RenderConfiguration& c, const PassPlan& pass,
                   FrameReport* report);
    void BindWaterPolygon(const FramePlan& plan);
    std::string BuildFourierGrid();
};

WaterRenderer::Impl::~Impl() {
    if (gl == nullptr || context == nullptr || !context->MakeCurrent()) {
        return;
    }
    for (auto& [id, program] : programs) {
        if (program.id != 0) {
            gl->glDeleteProgram(program.id);
        }
    }
    for (MeshBuffers& mesh : meshes) {
        gl->glDeleteBuffers(1, &mesh.vertices);
        gl->glDeleteBuffers(1, &mesh.indices);
    }
    gl->glDeleteBuffers(1, &sky_cube.vertices);
    gl->glDeleteBuffers(1, &sky_cube.indices);
    gl->glDeleteBuffers(1, &water_vertices);
    if (fourier_grid_built) {
        gl->glDeleteBuffers(1, &fourier_grid.vertices);
        gl->glDeleteBuffers(1, &fourier_grid.indices);
    }
    const GLuint textures[] = {sky_texture, normal_map, normalisation_cube};
    gl->glDeleteTextures(3, textures);
    for (RenderTarget* target : {&main, &low_res}) {
        FreeTarget(target);
    }
    for (auto* targets : {&reflection_targets, &refraction_targets}) {
        for (auto& [size, target] : *targets) {
            FreeTarget(&target);
        }
    }
}

GLuint WaterRenderer::Impl::UploadCube(const CubeMapImage& image) {
    GLuint texture = 0;
    gl->glGenTextures(1, &texture);
    gl->glBindTexture(GL_TEXTURE_CUBE_MAP, texture);
    for (int face = 0; face < 6; ++face) {
        const base::RgbaImage& side = image.faces[static_cast<std::size_t>(face)];
        gl->glTexImage2D(static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face), 0, GL_RGBA,
                         side.width, side.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, side.pixels.data());
    }
    gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

MeshBuffers WaterRenderer::Impl::UploadMesh(const Mesh& mesh) {
    std::vector<float> interleaved;
    interleaved.reserve(mesh.positions.size() * 9);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        for (const glm::vec3* v : {&mesh.positions[i], &mesh.normals[i], &mesh.colours[i]}) {
            interleaved.insert(interleaved.end(), {v->x, v->y, v->z});
        }
    }
    MeshBuffers buffers;
    gl->glGenBuffers(1, &buffers.vertices);
    gl->glBindBuffer(GL_ARRAY_BUFFER, buffers.vertices);
    gl->glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
                     interleaved.data(), GL_STATIC_DRAW);
    gl->glGenBuffers(1, &buffers.indices);
    gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers.indices);
    gl->glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                     static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint16_t)),
                     mesh.indices.data(), GL_STATIC_DRAW);
    buffers.index_count = static_cast<GLsizei>(mesh.indices.size());
    return buffers;
}

std::string WaterRenderer::Impl::MakeTarget(RenderTarget* target, int width, int height,
                                            GLenum internal_format, GLenum type, bool with_depth) {
    FreeTarget(target);
    target->width = width;
    target->height = height;
    gl->glGenTextures(1, &target->colour);
    gl->glBindTexture(GL_TEXTURE_2D, target->colour);
    gl->glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internal_format), width, height, 0,
                     GL_RGBA, type, nullptr);
    // Linear: the water samples these at screen coordinates that distortion moves off-centre.
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl->glGenFramebuffers(1, &target->framebuffer);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, target->framebuffer);
    gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target->colour,
                               0);
    if (with_depth) {
        gl->glGenRenderbuffers(1, &target->depth);
        gl->glBindRenderbuffer(GL_RENDERBUFFER, target->depth);
        // 24-bit depth: the water polygon reaches the far plane (2000 units, near 1).
        gl->glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
        gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                      target->depth);
    }
    const GLenum status = gl->glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        return fmt::format("a {}x{} render target is incomplete (status 0x{:x})", width, height,
                           status);
    }
    return "";
}

std::string WaterRenderer::Impl::EnsureTarget(std::map<int, RenderTarget>* targets, int size) {
    if (targets->find(size) != targets->end()) {
        return "";
    }
    RenderTarget target;
    std::string error = MakeTarget(&target, size, size, GL_RGBA8, GL_UNSIGNED_BYTE, true);
    if (!error.empty()) {
        FreeTarget(&target);
        return error;
    }
    targets->emplace(size, target);
    return "";
}

void WaterRenderer::Impl::FreeTarget(RenderTarget* target) {
    if (target->framebuffer != 0) {
        gl->glDeleteFramebuffers(1, &target->framebuffer);
        gl->glDeleteTextures(1, &target->colour);
    }
    if (target->depth != 0) {
        gl->glDeleteRenderbuffers(1, &target->depth);
    }
    *target = RenderTarget{};
}

std::string WaterRenderer::Impl::Init() {
    if (settings.width < 1 || settings.height < 1) {
        return fmt::format("the render size {}x{} is empty", settings.width, settings.height);
    }
    if (!scene_given) {
        scene = BuildDefaultScene();
    }
    meshes.push_back(UploadMesh(scene.terrain));
    terrain_reflection_colour =
            MeanLitColourAbove(scene.terrain, scene.water_height, scene.sun_direction);
    for (const Mesh& object : scene.objects) {
        meshes.push_back(UploadMesh(object));
    }

    // The unit cube around the camera for the sky; seen from inside, so drawn without culling.
    const std::vector<float> cube = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                                     -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
    const std::vector<std::uint16_t> cube_indices = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6,
                                                     0, 4, 5, 0, 5, 1, 3, 2, 6, 3, 6, 7,
                                                     0, 3, 7, 0, 7, 4, 1, 5, 6, 1, 6, 2};
    gl->glGenBuffers(1, &sky_cube.vertices);
    gl->glBindBuffer(GL_ARRAY_BUFFER, sky_cube.vertices);
    gl->glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(cube.size() * sizeof(float)),
                     cube.data(), GL_STATIC_DRAW);
    gl->glGenBuffers(1, &sky_cube.indices);
    gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, sky_cube.indices);
    gl->glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                     static_cast<GLsizeiptr>(cube_indices.size() * sizeof(std::uint16_t)),
                     cube_indices.data(), GL_STATIC_DRAW);
    sky_cube.index_count = static_cast<GLsizei>(cube_indices.size());

    gl->glGenBuffers(1, &water_vertices);
    gl->glBindBuffer(GL_ARRAY_BUFFER, water_vertices);
    gl->glBufferData(GL_ARRAY_BUFFER, kMaxWaterPolygonVertices * 3 * sizeof(float), nullptr,
                     GL_DYNAMIC_DRAW);

    gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl->glPixelStorei(GL_PACK_ALIGNMENT, 1);
    gl->glActiveTexture(GL_TEXTURE0 + kUnitSky);
    sky_texture = UploadCube(BuildSkyCubeMap(settings.sky_size, scene.sun_direction));
    gl->glActiveTexture(GL_TEXTURE0 + kUnitNormalisation);
    normalisation_cube = UploadCube(BuildNormalisationCubeMap(settings.normalisation_cube_size));
    gl->glActiveTexture(GL_TEXTURE0 + kUnitNormalMap);
    const base::RgbaImage normals = BuildWaterNormalMap(settings.normal_map_size);
    gl->glGenTextures(1, &normal_map);
    gl->glBindTexture(GL_TEXTURE_2D, normal_map);
    gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, normals.width, normals.height, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, normals.pixels.data());
    gl->glGenerateMipmap(GL_TEXTURE_2D);
    // Mipmapped and repeating: far water samples the map at many texels per pixel.
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    gl->glActiveTexture(GL_TEXTURE0);

    if (settings.float_target && !context->Environment().float_render_target) {
        return "float_target needs a context that renders to RGBA32F (GLES 3 with "
               "EXT_color_buffer_float, or desktop GL 3)";
    }
    std::string error = settings.float_target ? MakeTarget(&main, settings.width, settings.height,
                                                           GL_RGBA32F, GL_FLOAT, true)
                                              : MakeTarget(&main, settings.width, settings.height,
                                                           GL_RGBA8, GL_UNSIGNED_BYTE, true);
    if (error.empty()) {
        // With depth: the low-resolution pass draws the ground that hides water first.
        const int size = LowResWaterSize(settings);
        error = MakeTarget(&low_res, size, size, GL_RGBA8, GL_UNSIGNED_BYTE, true);
    }
    const GLenum gl_error = gl->glGetError();
    if (error.empty() && gl_error != GL_NO_ERROR) {
        error = ErrorName(gl_error) + " while creating the scene and render targets";
    }
    return error;
}

CompiledProgram& WaterRenderer::Impl::Program(const Variant& variant) {
    const std::string key = variant.Id();
    auto found = programs.find(key);
    if (found != programs.end()) {
        return found->second;
    }
    CompiledProgram& program = programs[key];
    DriverVerdict& verdict = program.verdict;
    const ProgramConfig* program_config = config.FindProgram(variant.program);
    std::string vertex_path;
    std::string fragment_path;
    if (program_config != nullptr) {
        vertex_path = program_config->vertex_path;
        fragment_path = program_config->fragment_path;
    } else {
        // Helper programs need not be listed in variants.yaml; they live next to the others.
        vertex_path = "shaders/" + variant.program + ".vsh";
        fragment_path = "shaders/" + variant.program + ".fsh";
    }
    const std::vector<std::string>& defines = variant.defines;
    GLuint shaders[2] = {0, 0};
    bool compiled[2] = {false, false};
    std::string* logs[2] = {&verdict.vertex_log, &verdict.fragment_log};
    const std::string* paths[2] = {&vertex_path, &fragment_path};
    for (int s = 0; s < 2; ++s) {
        const Stage stage = s == 0 ? Stage::kVertex : Stage::kFragment;
        const std::filesystem::path resolved = config.Resolve(*paths[s]);
        bool read_ok = true;
        auto cached = sources.find(resolved.string());
        if (cached == sources.end()) {
            cached = sources.emplace(resolved.string(), ReadText(resolved, &read_ok)).first;
            if (!read_ok) {
                sources.erase(cached);
                verdict.diagnostics.push_back(Diagnostic{
                        Severity::kError, *paths[s], 0, 0,
                        fmt::format("cannot read {} for the GL driver", resolved.string()), key});
                continue;
            }
        }
        const std::string source =
                AssembleDriverSource(cached->second, defines, stage, GlslTarget::kEs100);
        shaders[s] =
                gl->glCreateShader(stage == Stage::kVertex ? GL_VERTEX_SHADER : GL_FRAGMENT_SHADER);
        const char* text = source.c_str();
        gl->glShaderSource(shaders[s], 1, &text, nullptr);
        gl->glCompileShader(shaders[s]);
        GLint status = GL_FALSE;
        gl->glGetShaderiv(shaders[s], GL_COMPILE_STATUS, &status);
        GLint length = 0;
        gl->glGetShaderiv(shaders[s], GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        gl->glGetShaderInfoLog(shaders[s], length, nullptr, log.data());
        log.resize(std::strlen(log.c_str()));
        *logs[s] = log;
        compiled[s] = status == GL_TRUE;
        for (Diagnostic& d : ParseMesaInfoLog(log, *paths[s], key, cached->second)) {
            verdict.diagnostics.push_back(std::move(d));
        }
        if (!compiled[s] && !HasErrors(verdict.diagnostics)) {
            verdict.diagnostics.push_back(
                    Diagnostic{Severity::kError, *paths[s], 0, 0,
                               "the GL driver rejected the shader without an error message", key});
        }
    }
    verdict.vertex_compiled = compiled[0];
    verdict.fragment_compiled = compiled[1];
    if (compiled[0] && compiled[1]) {
        program.id = gl->glCreateProgram();
        gl->glAttachShader(program.id, shaders[0]);
        gl->glAttachShader(program.id, shaders[1]);
        gl->glBindAttribLocation(program.id, kAttribVertex, "inVertex");
        gl->glBindAttribLocation(program.id, kAttribNormal, "inNormal");
        gl->glBindAttribLocation(program.id, kAttribColour, "inColour");
        gl->glBindAttribLocation(program.id, kAttribFourier0, "inFourier0");
        gl->glBindAttribLocation(program.id, kAttribFourier1, "inFourier1");
        gl->glLinkProgram(program.id);
        GLint status = GL_FALSE;
        gl->glGetProgramiv(program.id, GL_LINK_STATUS, &status);
        GLint length = 0;
        gl->glGetProgramiv(program.id, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        gl->glGetProgramInfoLog(program.id, length, nullptr, log.data());
        log.resize(std::strlen(log.c_str()));
        verdict.link_log = log;
        verdict.linked = status == GL_TRUE;
        // Link messages name no line; they belong to the program's vertex file.
        for (Diagnostic& d : ParseMesaInfoLog(log, vertex_path, key)) {
            d.line = 0;
            verdict.diagnostics.push_back(std::move(d));
        }
        if (!verdict.linked && !HasErrors(verdict.diagnostics)) {
            verdict.diagnostics.push_back(Diagnostic{
                    Severity::kError, vertex_path, 0, 0,
                    "the GL driver refused to link the program without an error message", key});
        }
    }
    for (GLuint shader : shaders) {
        if (shader != 0) {
            gl->glDeleteShader(shader);
        }
    }
    verdict.valid = verdict.linked;
    program.valid = verdict.valid;
    if (!program.valid && program.id != 0) {
        gl->glDeleteProgram(program.id);
        program.id = 0;
    }
    return program;
}

GLint WaterRenderer::Impl::Uniform(CompiledProgram& program, const char* name) {
    auto found = program.uniforms.find(name);
    if (found != program.uniforms.end()) {
        return found->second;
    }
    const GLint location = gl->glGetUniformLocation(program.id, name);
    program.uniforms.emplace(name, location);
    return location;
}

void WaterRenderer::Impl::DrawSky(const PassPlan& pass, FrameReport* report) {
    CompiledProgram& program = Program(pass.sky_program);
    if (!program.valid) {
        return;
    }
    gl->glUseProgram(program.id);
    // Rotation only: the sky must not move with the camera.
    const glm::mat4 rotation(glm::mat3(pass.view));
    const glm::mat4 mvp = pass.projection * rotation;
    gl->glUniformMatrix4fv(Uniform(program, "ModelViewProjMatrix"), 1, GL_FALSE,
                           glm::value_ptr(mvp));
    gl->glUniform1i(Uniform(program, "SkyboxTex"), kUnitSky);
    gl->glUniform3f(Uniform(program, "FogColour"), settings.fog_colour.r, settings.fog_colour.g,
                    settings.fog_colour.b);
    // The sky's eye is the real camera's for the unmirrored view, the mirrored one otherwise;
    // only its clip test uses it, against the world-space plane.
    const glm::vec3 eye = glm::vec3(glm::inverse(pass.view)[3]);
    gl->glUniform3f(Uniform(program, "EyePosition"), eye.x, eye.y, eye.z);
    gl->glUniform4f(Uniform(program, "ClipPlane"), pass.clip_plane.x, pass.clip_plane.y,
                    pass.clip_plane.z, pass.clip_plane.w);
    gl->glDisable(GL_CULL_FACE);
    gl->glBindBuffer(GL_ARRAY_BUFFER, sky_cube.vertices);
    gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, sky_cube.indices);
    gl->glEnableVertexAttribArray(kAttribVertex);
    gl->glVertexAttribPointer(kAttribVertex, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
    gl->glDisableVertexAttribArray(kAttribNormal);
    gl->glDisableVertexAttribArray(kAttribColour);
    gl->glDrawElements(GL_TRIANGLES, sky_cube.index_count, GL_UNSIGNED_SHORT, nullptr);
    ++report->draw_calls;
}

void WaterRenderer::Impl::DrawModels(const PassPlan& pass, FrameReport* report) {
    CompiledProgram& program = Program(pass.model_program);
    if (!program.valid || pass.meshes.empty()) {
        return;
    }
    gl->glUseProgram(program.id);
    gl->glUniform3f(Uniform(program, "LightDirection"), scene.sun_direction.x,
                    scene.sun_direction.y, scene.sun_direction.z);
    gl->glUniform1f(Uniform(program, "WaterHeight"), scene.water_height);
    gl->glUniform1f(Uniform(program, "RcpMaxWaterDepth"),
                    MediumpFogReciprocal(1.0F / MediumpMaxWaterDepth(settings.max_water_depth)));
    gl->glUniform1f(Uniform(program, "RcpMaxFogDepth"),
                    MediumpFogReciprocal(settings.rcp_max_fog_depth));
    gl->glUniform3f(Uniform(program, "FogColour"), settings.underwater_colour.r,
                    settings.underwater_colour.g, settings.underwater_colour.b);
    gl->glUniform4f(Uniform(program, "ClipPlane"), pass.clip_plane.x, pass.clip_plane.y,
                    pass.clip_plane.z, pass.clip_plane.w);
    const GLint mvp_location = Uniform(program, "ModelViewProjMatrix");
    const GLint model_location = Uniform(program, "ModelMatrix");
    const glm::mat4 view_projection = pass.projection * pass.view;
    gl->glEnable(GL_CULL_FACE);
    gl->glEnableVertexAttribArray(kAttribVertex);
    gl->glEnableVertexAttribArray(kAttribNormal);
    gl->glEnableVertexAttribArray(kAttribColour);
    constexpr GLsizei kStride = 9 * sizeof(float);
    for (int index : pass.meshes) {
        const Mesh& mesh =
                index < 0 ? scene.terrain : scene.objects[static_cast<std::size_t>(index)];
        // meshes holds the terrain (index -1) first, then scene.objects.
        const MeshBuffers& buffers = meshes[index < 0 ? 0 : static_cast<std::size_t>(index) + 1];
        const glm::mat4 mvp = view_projection * mesh.model_matrix;
        gl->glUniformMatrix4fv(mvp_location, 1, GL_FALSE, glm::value_ptr(mvp));
        gl->glUniformMatrix4fv(model_location, 1, GL_FALSE, glm::value_ptr(mesh.model_matrix));
        gl->glBindBuffer(GL_ARRAY_BUFFER, buffers.vertices);
        gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers.indices);
        gl->glVertexAttribPointer(kAttribVertex, 3, GL_FLOAT, GL_FALSE, kStride, nullptr);
        gl->glVertexAttribPointer(kAttribNormal, 3, GL_FLOAT, GL_FALSE, kStride,
                                  BufferOffset(3 * sizeof(float)));
        gl->glVertexAttribPointer(kAttribColour, 3, GL_FLOAT, GL_FALSE, kStride,
                                  BufferOffset(6 * sizeof(float)));
        gl->glDrawElements(GL_TRIANGLES, buffers.index_count, GL_UNSIGNED_SHORT, nullptr);
        ++report->draw_calls;
    }
    gl->glDisable(GL_CULL_FACE);
}

void WaterRenderer::Impl::BindWaterPolygon(const FramePlan& plan) {
    gl->glBindBuffer(GL_ARRAY_BUFFER, water_vertices);
    gl->glEnableVertexAttribArray(kAttribVertex);
    gl->glVertexAttribPointer(kAttribVertex, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
    gl->glDisableVertexAttribArray(kAttribNormal);
    gl->glDisableVertexAttribArray(kAttribColour);
    (void)plan;
}

void WaterRenderer::Impl::DrawWater(const FramePlan& plan, const RenderConfiguration& c,
                                    const PassPlan& pass, FrameReport* report) {
    const bool alpha_blend =
            c.Has(ShaderFeature::kAlphaBlend) && !c.Has(ShaderFeature::kRefraction);
    const auto vertex_count = static_cast<GLsizei>(plan.polygon.size());
    BindWaterPolygon(plan);
    if (pass.water_program.program == "water_composite") {
        CompiledProgram& composite = Program(pass.water_program);
        if (!composite.valid) {
            return;
        }
        gl->glUseProgram(composite.id);
        gl->glUniformMatrix4fv(Uniform(composite, "ModelViewProjMatrix"), 1, GL_FALSE,
                               glm::value_ptr(plan.view_projection));
        gl->glUniform2f(Uniform(composite, "RcpWindowSize"),
                        1.0F / static_cast<float>(settings.width),
                        1.0F / static_cast<float>(settings.height));
        gl->glActiveTexture(GL_TEXTURE0 + kUnitLowRes);
        gl->glBindTexture(GL_TEXTURE_2D, low_res.colour);
        gl->glActiveTexture(GL_TEXTURE0);
        gl->glUniform1i(Uniform(composite, "WaterTex"), kUnitLowRes);
        if (alpha_blend) {
            gl->glEnable(GL_BLEND);
            gl->glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        }
        gl->glDrawArrays(GL_TRIANGLE_FAN, 0, vertex_count);
        ++report->draw_calls;
        gl->glDisable(GL_BLEND);
        return;
    }
    CompiledProgram& program = Program(pass.water_program);
    if (!program.valid) {
        return;
    }
    gl->glUseProgram(program.id);
    const auto target_width = static_cast<float>(pass.width);
    const auto target_height = static_cast<float>(pass.height);
    gl->glUniformMatrix4fv(Uniform(program, "ModelViewProjMatrix"), 1, GL_FALSE,
                           glm::value_ptr(plan.view_projection));
    gl->glUniform3f(Uniform(program, "EyePosition"), plan.eye.x, plan.eye.y, plan.eye.z);
    gl->glUniform2f(Uniform(program, "BumpScale0"), settings.bump_scale0.x, settings.bump_scale0.y);
    gl->glUniform2f(Uniform(program, "BumpScale1"), settings.bump_scale1.x, settings.bump_scale1.y);
    gl->glUniform2f(Uniform(program, "BumpTranslation0"), plan.bump_translation0.x,
                    plan.bump_translation0.y);
    gl->glUniform2f(Uniform(program, "BumpTranslation1"), plan.bump_translation1.x,
                    plan.bump_translation1.y);
    gl->glUniform1f(Uniform(program, "WaveDistortion"), plan.wave_distortion);
    gl->glUniform2f(Uniform(program, "RcpWindowSize"), 1.0F / target_width, 1.0F / target_height);
    gl->glUniform4f(Uniform(program, "WaterColour"), settings.water_colour.r,
                    settings.water_colour.g, settings.water_colour.b, settings.water_colour.a);
    gl->glUniform3f(Uniform(program, "FogColour"), settings.fog_colour.r, settings.fog_colour.g,
                    settings.fog_colour.b);
    gl->glUniform1f(Uniform(program, "RcpMaxFogDepth"),
                    MediumpFogReciprocal(settings.rcp_max_fog_distance));
    gl->glUniform1i(Uniform(program, "ReflectionTex"), kUnitReflection);
    gl->glUniform1i(Uniform(program, "RefractionTex"), kUnitRefraction);
    gl->glUniform1i(Uniform(program, "NormalTex"), kUnitNormalMap);
    gl->glUniform1i(Uniform(program, "NormalisationCubeMap"), kUnitNormalisation);
    gl->glUniform1i(Uniform(program, "SkyboxTex"), kUnitSky);
    gl->glUniform3f(Uniform(program, "TerrainReflectionColour"), terrain_reflection_colour.r,
                    terrain_reflection_colour.g, terrain_reflection_colour.b);
    gl->glUniform1f(Uniform(program, "MaxWaterDepth"),
                    MediumpMaxWaterDepth(settings.max_water_depth));
    const ExtinctionModel& extinction = settings.extinction;
    gl->glUniform3f(Uniform(program, "Extinction"), extinction.extinction.r,
                    extinction.extinction.g, extinction.extinction.b);
    gl->glUniform1f(Uniform(program, "Visibility"), extinction.visibility);
    gl->glUniform3f(Uniform(program, "SurfaceColour"), extinction.surface_colour.r,
                    extinction.surface_colour.g, extinction.surface_colour.b);
    gl->glUniform3f(Uniform(program, "DepthColour"), extinction.depth_colour.r,
                    extinction.depth_colour.g, extinction.depth_colour.b);
    gl->glUniform3f(Uniform(program, "FoamColour"), settings.foam_colour.r, settings.foam_colour.g,
                    settings.foam_colour.b);
    gl->glUniform2f(Uniform(program, "FoamDepth"), settings.foam_depth.x, settings.foam_depth.y);
    gl->glUniform2f(Uniform(program, "FoamScale"), settings.foam_scale.x, settings.foam_scale.y);
    gl->glUniform1f(Uniform(program, "ShoreHardness"), settings.shore_hardness);
    gl->glUniform3f(Uniform(program, "SunDirection"), scene.sun_direction.x, scene.sun_direction.y,
                    scene.sun_direction.z);
    gl->glUniform3f(Uniform(program, "SunColour"), settings.sun_colour.r, settings.sun_colour.g,
                    settings.sun_colour.b);
    gl->glUniform1f(Uniform(program, "Shininess"), settings.shininess);
    if (c.UsesUniformBools()) {
        // The water effects water_uniform reads as uniform bools (INTERFACE.md).
        for (const ShaderFeatureInfo& feature : kShaderFeatures) {
            if (feature.uniform_bool) {
                gl->glUniform1i(Uniform(program, UniformBoolName(feature.define).c_str()),
                                c.Has(feature.feature) ? 1 : 0);
            }
        }
    }
    gl->glActiveTexture(GL_TEXTURE0 + kUnitReflection);
    gl->glBindTexture(GL_TEXTURE_2D, reflection.colour);
    gl->glActiveTexture(GL_TEXTURE0 + kUnitRefraction);
    // Without a refraction pass the sampler still needs a complete texture behind it.
    gl->glBindTexture(GL_TEXTURE_2D, c.Has(ShaderFeature::kRefraction) && refraction.colour != 0
                                             ? refraction.colour
                                             : reflection.colour);
    gl->glActiveTexture(GL_TEXTURE0);
    if (alpha_blend && pass.kind == PassKind::kMain) {
        gl->glEnable(GL_BLEND);
        gl->glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    }
    if (c.Has(ShaderFeature::kReflectionFourier) && fourier_grid_built) {
        // The tessellated grid: the coefficients vary per vertex, so the single polygon that
        // covers the view will not do.
        constexpr GLsizei kStride = 11 * sizeof(float);
        gl->glBindBuffer(GL_ARRAY_BUFFER, fourier_grid.vertices);
        gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, fourier_grid.indices);
        gl->glVertexAttribPointer(kAttribVertex, 3, GL_FLOAT, GL_FALSE, kStride, nullptr);
        gl->glEnableVertexAttribArray(kAttribFourier0);
        gl->glEnableVertexAttribArray(kAttribFourier1);
        gl->glVertexAttribPointer(kAttribFourier0, 4, GL_FLOAT, GL_FALSE, kStride,
                                  BufferOffset(3 * sizeof(float)));
        gl->glVertexAttribPointer(kAttribFourier1, 4, GL_FLOAT, GL_FALSE, kStride,
                                  BufferOffset(7 * sizeof(float)));
        gl->glDrawElements(GL_TRIANGLES, fourier_grid.index_count, GL_UNSIGNED_SHORT, nullptr);
        gl->glDisableVertexAttribArray(kAttribFourier0);
        gl->glDisableVertexAttribArray(kAttribFourier1);
    } else {
        gl->glDrawArrays(GL_TRIANGLE_FAN, 0, vertex_count);
    }
    ++report->draw_calls;
    gl->glDisable(GL_BLEND);
}

std::string WaterRenderer::Impl::BuildFourierGrid() {
    if (fourier_grid_built || !fourier_grid_error.empty()) {
        return fourier_grid_error;
    }
    fourier_grid_error = CheckFourierSettings(settings.fourier);
    if (!fourier_grid_error.empty()) {
        return fourier_grid_error;
    }
    const FourierWaterGrid grid = BuildFourierWaterGrid(scene, settings.fourier);
    if (grid.positions.empty() || grid.indices.empty()) {
        fourier_grid_error =
                "the Fourier water grid is empty (over 65535 vertices? raise "
                "fourier grid spacing)";
        return fourier_grid_error;
    }
    std::vector<float> interleaved;
    interleaved.reserve(grid.positions.size() * 11);
    for (std::size_t i = 0; i < grid.positions.size(); ++i) {
        const glm::vec3& p = grid.positions[i];
        const glm::vec4& c0 = grid.coefficients0[i];
        const glm::vec4& c1 = grid.coefficients1[i];
        interleaved.insert(interleaved.end(),
                           {p.x, p.y, p.z, c0.x, c0.y, c0.z, c0.w, c1.x, c1.y, c1.z, c1.w});
    }
    gl->glGenBuffers(1, &fourier_grid.vertices);
    gl->glBindBuffer(GL_ARRAY_BUFFER, fourier_grid.vertices);
    gl->glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)),
                     interleaved.data(), GL_STATIC_DRAW);
    gl->glGenBuffers(1, &fourier_grid.indices);
    gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, fourier_grid.indices);
    gl->glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                     static_cast<GLsizeiptr>(grid.indices.size() * sizeof(std::uint16_t)),
                     grid.indices.data(), GL_STATIC_DRAW);
    fourier_grid.index_count = static_cast<GLsizei>(grid.indices.size());
    fourier_grid_built = true;
    return "";
}

WaterRenderer::WaterRenderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

WaterRenderer::~WaterRenderer() = default;

std::unique_ptr<WaterRenderer> WaterRenderer::Create(GlContext& context,
                                                     const VariantConfig& config,
                                                     const RenderSettings& settings,
                                                     std::string* error, const Scene* scene) {
    if (!context.MakeCurrent()) {
        *error = "the GL context cannot be made current";
        return nullptr;
    }
    auto impl = std::make_unique<Impl>();
    impl->context = &context;
    impl->gl = &context.Internal().api;
    impl->timer_query = &context.Internal().timer_query;
    impl->config = config;
    impl->settings = settings;
    if (scene != nullptr) {
        impl->scene = *scene;
        impl->scene_given = true;
    }
    *error = impl->Init();
    if (!error->empty()) {
        return nullptr;
    }
    return std::unique_ptr<WaterRenderer>(new WaterRenderer(std::move(impl)));
}

DriverVerdict WaterRenderer::Prepare(const RenderConfiguration& c) {
    Impl& r = *impl_;
    r.context->MakeCurrent();
    DriverVerdict verdict = r.Program(c.variant).verdict;
    // Helper programs this configuration's passes can use; their problems join the verdict.
    const std::vector<Variant> helpers = HelperPrograms(c);
    if (c.Has(ShaderFeature::kReflectionFourier)) {
        const std::string error = r.BuildFourierGrid();
        if (!error.empty()) {
            verdict.valid = false;
            verdict.diagnostics.push_back(MakeError("", 0, 0, error));
        }
    }
    for (const Variant& helper : helpers) {
        const DriverVerdict& helper_verdict = r.Program(helper).verdict;
        if (!helper_verdict.valid) {
            verdict.valid = false;
            for (Diagnostic d : helper_verdict.diagnostics) {
                verdict.diagnostics.push_back(std::move(d));
            }
        }
    }
    // Reflection and refraction targets of the configuration's sizes.
    const int width = r.settings.width;
    const int height = r.settings.height;
    for (auto [targets, size] :
         {std::pair{&r.reflection_targets, ReflectionSize(c.passes, width, height)},
          std::pair{&r.refraction_targets, RefractionSize(c.passes, width, height)}}) {
        if (!verdict.valid) {
            break;
        }
        const std::string error = r.EnsureTarget(targets, size);
        if (!error.empty()) {
            verdict.valid = false;
            verdict.diagnostics.push_back(MakeError("", 0, 0, error));
        }
    }
    return verdict;
}

FrameReport WaterRenderer::RenderFrame(const RenderConfiguration& c, const CameraView& view,
                                       const PassCallback& after_pass) {
    Impl& r = *impl_;
    const gl::GlApi& gl = *r.gl;
    FrameReport report;
    const auto plan_start = std::chrono::steady_clock::now();
    const FramePlan plan = PlanFrame(c, r.settings, r.scene, view);
    report.plan_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - plan_start).count();
    report.oblique_fallback = plan.oblique_fallback;
    const auto reflection = r.reflection_targets.find(
            ReflectionSize(c.passes, r.settings.width, r.settings.height));
    const auto refraction = r.refraction_targets.find(
            RefractionSize(c.passes, r.settings.width, r.settings.height));
    if (reflection == r.reflection_targets.end() || refraction == r.refraction_targets.end()) {
        report.gl_error = "RenderFrame before a successful Prepare of this configuration";
        return report;
    }
    r.reflection = reflection->second;
    r.refraction = refraction->second;
    if (!plan.polygon.empty()) {
        std::array<float, kMaxWaterPolygonVertices * 3> data{};
        for (std::size_t i = 0; i < plan.polygon.size(); ++i) {
            data[i * 3] = plan.polygon[i].x;
            data[i * 3 + 1] = plan.polygon[i].y;
            data[i * 3 + 2] = plan.polygon[i].z;
        }
        gl.glBindBuffer(GL_ARRAY_BUFFER, r.water_vertices);
        gl.glBufferSubData(GL_ARRAY_BUFFER, 0,
                           static_cast<GLsizeiptr>(plan.polygon.size() * 3 * sizeof(float)),
                           data.data());
    }
    gl.glDepthFunc(GL_LEQUAL);  // LEQUAL: the sky sits exactly on the cleared depth 1.0
    for (const PassPlan& pass : plan.passes) {
        const RenderTarget& target = pass.kind == PassKind::kReflection    ? r.reflection
                                     : pass.kind == PassKind::kRefraction  ? r.refraction
                                     : pass.kind == PassKind::kLowResWater ? r.low_res
                                                                           : r.main;
        gl.glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
        gl.glViewport(0, 0, target.width, target.height);
        ++report.passes;
        report.pass_names.emplace_back(PassName(pass.kind));
        report.pass_pixels.push_back(static_cast<long long>(target.width) * target.height);
        const int draws_before = report.draw_calls;
        gl.glClearColor(pass.clear_colour.r, pass.clear_colour.g, pass.clear_colour.b,
                        pass.clear_colour.a);
        gl.glDepthMask(GL_TRUE);
        gl.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gl.glEnable(GL_DEPTH_TEST);
        // The mirror matrix has determinant -1, so mirrored triangles wind clockwise.
        gl.glFrontFace(pass.mirrored ? GL_CW : GL_CCW);
        if (pass.draw_sky) {
            r.DrawSky(pass, &report);
        }
        r.DrawModels(pass, &report);
        if (pass.draw_water) {
            r.DrawWater(plan, c, pass, &report);
        }
        gl.glFrontFace(GL_CCW);
        report.pass_draw_calls.push_back(report.draw_calls - draws_before);
        const GLenum error = gl.glGetError();
        if (error != GL_NO_ERROR && report.gl_error.empty()) {
            report.gl_error =
                    fmt::format("{} after pass {}", ErrorName(error), PassName(pass.kind));
        }
        if (after_pass) {
            after_pass(report.pass_names.back());
        }
    }
    return report;
}

bool WaterRenderer::BeginGpuTimer() {
    Impl& r = *impl_;
    const gl::GlTimerQueryApi& q = *r.timer_query;
    if (!q.Available() || r.gpu_query_running) {
        return false;
    }
    if (r.gpu_query == 0) {
        q.glGenQueriesEXT(1, &r.gpu_query);
    }
    GLint disjoint = 0;
    r.gl->glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);  // reading it clears the flag
    q.glBeginQueryEXT(GL_TIME_ELAPSED_EXT, r.gpu_query);
    r.gpu_query_running = true;
    return true;
}

double WaterRenderer::EndGpuTimerMs() {
    Impl& r = *impl_;
    const gl::GlTimerQueryApi& q = *r.timer_query;
    if (!r.gpu_query_running) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    q.glEndQueryEXT(GL_TIME_ELAPSED_EXT);
    r.gpu_query_running = false;
    GLuint64 nanoseconds = 0;
    q.glGetQueryObjectui64vEXT(r.gpu_query, GL_QUERY_RESULT_EXT, &nanoseconds);  // waits
    GLint disjoint = 0;
    r.gl->glGetIntegerv(GL_GPU_DISJOINT_EXT, &disjoint);
    return disjoint != 0 ? std::numeric_limits<double>::quiet_NaN()
                         : static_cast<double>(nanoseconds) * 1e-6;
}

void WaterRenderer::UpdateFrameSettings(const RenderSettings& settings) {
    RenderSettings& kept = impl_->settings;
    RenderSettings updated = settings;
    updated.width = kept.width;
    updated.height = kept.height;
    updated.low_res_water_size = kept.low_res_water_size;
    updated.sky_size = kept.sky_size;
    updated.normal_map_size = kept.normal_map_size;
    updated.normalisation_cube_size = kept.normalisation_cube_size;
    updated.float_target = kept.float_target;
    kept = updated;
}

void WaterRenderer::Finish() {
    impl_->gl->glFinish();
}

base::RgbaImage WaterRenderer::ReadImage() {
    Impl& r = *impl_;
    base::RgbaImage image;
    image.width = r.settings.width;
    image.height = r.settings.height;
    const auto row_bytes = static_cast<std::size_t>(image.width) * 4;
    image.pixels.resize(row_bytes * static_cast<std::size_t>(image.height));
    r.gl->glBindFramebuffer(GL_FRAMEBUFFER, r.main.framebuffer);
    std::vector<std::uint8_t> bottom_up(image.pixels.size());
    if (r.settings.float_target) {
        const std::vector<float> floats = ReadFloatPixels();
        for (std::size_t i = 0; i < floats.size(); ++i) {
            const float v = std::isfinite(floats[i]) ? std::clamp(floats[i], 0.0F, 1.0F) : 0.0F;
            image.pixels[i] = static_cast<std::uint8_t>(std::lround(v * 255.0F));
        }
        return image;
    }
    r.gl->glReadPixels(0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                       bottom_up.data());
    for (int row = 0; row < image.height; ++row) {
        std::copy_n(bottom_up.begin() +
                            static_cast<std::ptrdiff_t>(
                                    row_bytes * static_cast<std::size_t>(image.height - 1 - row)),
                    row_bytes,
                    image.pixels.begin() +
                            static_cast<std::ptrdiff_t>(row_bytes * static_cast<std::size_t>(row)));
    }
    return image;
}

std::vector<float> WaterRenderer::ReadFloatPixels() {
    Impl& r = *impl_;
    if (!r.settings.float_target) {
        return {};
    }
    const auto row_floats = static_cast<std::size_t>(r.settings.width) * 4;
    std::vector<float> bottom_up(row_floats * static_cast<std::size_t>(r.settings.height));
    r.gl->glBindFramebuffer(GL_FRAMEBUFFER, r.main.framebuffer);
    r.gl->glReadPixels(0, 0, r.settings.width, r.settings.height, GL_RGBA, GL_FLOAT,
                       bottom_up.data());
    std::vector<float> pixels(bottom_up.size());
    for (int row = 0; row < r.settings.height; ++row) {
        std::copy_n(
                bottom_up.begin() +
                        static_cast<std::ptrdiff_t>(
                                row_floats * static_cast<std::size_t>(r.settings.height - 1 - row)),
                row_floats,
                pixels.begin() +
                        static_cast<std::ptrdiff_t>(row_floats * static_cast<std::size_t>(row)));
    }
    return pixels;
}

const RenderSettings& WaterRenderer::Settings() const {
    return impl_->settings;
}

const Scene& WaterRenderer::GetScene() const {
    return impl_->scene;
}

DriverStageResult CompileDriverStage(GlContext& context, Stage stage, const std::string& source) {
    DriverStageResult result;
    if (!context.MakeCurrent()) {
        result.log = "the GL context cannot be made current";
        return result;
    }
    const gl::GlApi& gl = context.Internal().api;
    const GLuint shader =
            gl.glCreateShader(stage == Stage::kVertex ? GL_VERTEX_SHADER : GL_FRAGMENT_SHADER);
    const char* text = source.c_str();
    gl.glShaderSource(shader, 1, &text, nullptr);
    gl.glCompileShader(shader);
    GLint status = GL_FALSE;
    gl.glGetShaderiv(shader, GL_COMPILE_STATUS, &status);
    GLint length = 0;
    gl.glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    gl.glGetShaderInfoLog(shader, length, nullptr, log.data());
    log.resize(std::strlen(log.c_str()));
    gl.glDeleteShader(shader);
    result.compiled = status == GL_TRUE;
    result.log = log;
    return result;
}

}  // namespace tidepool::runner
