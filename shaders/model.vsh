#version 100
// Terrain and objects, vertex stage. Interface: shaders/INTERFACE.md ("model").
//
// Defines:
//   ENABLE_LIGHTING   Lambert diffuse plus ambient, albedo * (0.35 + 0.65 * max(N.L, 0)),
//                     evaluated per vertex: diffuse light varies slowly across a triangle, and
//                     the fragment stage (the expensive one on a software rasteriser) then only
//                     passes the lit colour on. Costs a normal transform, a normalisation and a
//                     dot product per vertex.
//   ENABLE_FOG_DEPTH  Passes the depth below the water plane for underwater fog (refraction
//                     pass). Costs one varying.
//   ENABLE_DEPTH_ALPHA  The same depth, for model.fsh to store in alpha (refraction pass of the
//                     depth-based optics). Shares the varying with ENABLE_FOG_DEPTH.
//   CLIP_DISCARD      Passes the signed distance to ClipPlane for the fragment stage to discard
//                     on. Costs one varying (see model.fsh for the discard's cost).
// Without ENABLE_LIGHTING the model shows its albedo unlit.

attribute highp vec3 inVertex;
attribute mediump vec3 inNormal;
attribute lowp vec3 inColour;

uniform highp mat4 ModelViewProjMatrix;

#if defined(ENABLE_FOG_DEPTH) || defined(ENABLE_DEPTH_ALPHA)
#define NEEDS_WATER_DEPTH
#endif

#if defined(ENABLE_LIGHTING) || defined(NEEDS_WATER_DEPTH) || defined(CLIP_DISCARD)
#define NEEDS_MODEL_MATRIX
#endif

#ifdef NEEDS_MODEL_MATRIX
uniform highp mat4 ModelMatrix;
#endif

#ifdef ENABLE_LIGHTING
uniform mediump vec3 LightDirection;

// Share of the albedo that is lit regardless of orientation, so faces turned away from the sun
// are dark but not black.
const mediump float cAmbient = 0.35;
const mediump float cDiffuse = 0.65;
#endif

#ifdef NEEDS_WATER_DEPTH
uniform highp float WaterHeight;

// Depth below the water surface (negative above it). It is linear in the position, so per-vertex
// evaluation and interpolation give the exact per-fragment value.
varying mediump float WaterDepth;
#endif

#ifdef CLIP_DISCARD
uniform highp vec4 ClipPlane;

// Signed distance to the clip plane, linear in the position like WaterDepth. highp because only
// its sign matters and the sign flips where the value is close to zero.
varying highp float ClipDistance;
#endif

// Albedo, lit when ENABLE_LIGHTING is on.
varying lowp vec3 Colour;

void main()
{
    gl_Position = ModelViewProjMatrix * vec4(inVertex, 1.0);

#ifdef NEEDS_MODEL_MATRIX
    highp vec3 worldPosition = (ModelMatrix * vec4(inVertex, 1.0)).xyz;
#endif

#ifdef ENABLE_LIGHTING
    // ModelMatrix is rigid with uniform scale, so its upper 3x3 (w = 0 drops the translation)
    // maps normals correctly up to a length, which the normalisation removes; no inverse
    // transpose is needed. (GLSL ES 1.00 has no mat3(mat4) constructor.)
    // normalize() with a floor under the squared length: a degenerate zero normal in the mesh
    // then lights as ambient only instead of turning the vertex NaN.
    highp vec3 worldNormal = (ModelMatrix * vec4(inNormal, 0.0)).xyz;
    mediump vec3 normal = worldNormal * inversesqrt(max(dot(worldNormal, worldNormal), 1e-8));
    mediump float diffuse = max(dot(normal, LightDirection), 0.0);
    Colour = inColour * (cAmbient + cDiffuse * diffuse);
#else
    Colour = inColour;
#endif

#ifdef NEEDS_WATER_DEPTH
    WaterDepth = WaterHeight - worldPosition.y;
#endif

#ifdef CLIP_DISCARD
    ClipDistance = dot(ClipPlane, vec4(worldPosition, 1.0));
#endif
}
