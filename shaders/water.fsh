#version 100
// Water surface, fragment stage: a screen-space lookup into the reflection (and refraction) pass
// textures, perturbed by animated bump layers. Interface: shaders/INTERFACE.md ("water").
// Costs quoted are the whitepaper's (PowerVR SGX class); this renderer measures its own.
//
// Defines:
//   ENABLE_DISTORTION        Ripples: two NormalTex samples offset the screen-space lookup by
//                            their mean normal times WaveDistortion, in texture units (the
//                            demo's convention). Buys a moving surface; costs two dependent
//                            texture reads.
//   ENABLE_SCALE_DISTORTION  Divides the offset by the eye distance so far water does not shimmer
//                            more than near water. Needs ENABLE_DISTORTION. Costs a length and a
//                            divide (whitepaper: <1%). Without it the renderer sets WaveDistortion
//                            to give the same offset at the view's typical water distance.
//   ENABLE_REFRACTION        Mixes in RefractionTex (0.4 reflection). Buys visible depths; costs a
//                            whole extra render pass plus a texture read (whitepaper: -60%).
//   ENABLE_FRESNEL           Schlick's angle-dependent mix instead of the constant 0.4.
//                            Needs ENABLE_REFRACTION. Costs the eye direction (from the squared
//                            length the eye distance already needs), a dot product with the
//                            accumulated normal as it is, and a few multiplies (whitepaper: -22%).
//   FRESNEL_EXACT            Full unpolarised dielectric Fresnel equations instead of Schlick.
//                            Needs ENABLE_FRESNEL. Buys exact reflectance at all angles; costs a
//                            sqrt, two divides and more arithmetic.
//   NORMALISE_CUBEMAP        Normalises the eye vector by a NormalisationCubeMap lookup instead
//                            of arithmetic. Needs ENABLE_FRESNEL. Cheaper on hardware where the
//                            texture unit is idle (whitepaper: "can halve the cycles"); costs
//                            8-bit precision in the direction.
//   ENABLE_WATER_COLOUR      Mixes the reflection with WaterColour (murky water) instead of
//                            refracting. Ignored with ENABLE_REFRACTION. (whitepaper: -9%)
//   ENABLE_ALPHA_BLEND       Outputs alpha 0.6 so the scene under the water shows through the
//                            blend instead of refracting. Ignored with ENABLE_REFRACTION.
//                            Costs framebuffer blending (whitepaper: -11%).
//   ENABLE_FOG               Fades the water towards FogColour with eye distance. Costs a
//                            length and a mix (whitepaper: disabling it gave +3.5%).
//
// Reflection technique (the REFLECTION axis of variants.yaml; at most one of these is defined):
//   (neither)                Planar: ReflectionTex, a mirrored render of the scene, sampled at
//                            the screen coordinate. Shows everything; costs a whole render pass.
//   REFLECTION_CUBEMAP       The view ray reflected about the bumped normal (tilted by the
//                            planar lookup's offset, the same convention) looks up SkyboxTex
//                            (../shared/seeds/001). No reflection pass; shows only the sky, so
//                            terrain and objects are missing from the reflection.
//   REFLECTION_FOURIER       As cubemap, but where the reflected ray's elevation lies below the
//                            terrain's elevation angle in its azimuth, evaluated from per-vertex
//                            Fourier coefficients (../shared/seeds/004), it shows
//                            TerrainReflectionColour. No reflection pass; the terrain reflects
//                            as one flat colour and objects are missing.
//
// Depth-based optics (../shared/seeds/003). The refraction pass stores the vertical water depth
// D of what it sees in its alpha channel as sqrt(D / MaxWaterDepth) (shaders/model.fsh,
// ENABLE_DEPTH_ALPHA); each of these needs ENABLE_REFRACTION and is a no-op without it:
//   ENABLE_EXTINCTION        Per-channel colour extinction with depth, and horizontal visibility:
//                            r = mix(r, SurfaceColour, clamp(L / Visibility, 0, 1)), then
//                            r = mix(r, DepthColour, clamp(D / Extinction, 0, 1)) per channel,
//                            where r is the refracted colour and L = D / max(cos view, 0.05)
//                            the path through the water (Extinction default 4.5, 75, 300).
//   ENABLE_SHORE_FOAM        Foam where the water is shallow: full up to FoamDepth.x, gone at
//                            FoamDepth.y, patterned by NormalTex reused as a noise texture.
//   ENABLE_SOFT_SHORE        Blends back to the refraction where D * ShoreHardness < 1, so the
//                            water meets the shore without a hard edge.
//   ENABLE_SUN_SPECULAR      The seed's sun glare: pow(reflected-eye · sun, 512) weighted by
//                            (1 - Fresnel) and Shininess, evaluated in a form that does not
//                            band at mediump. Needs ENABLE_FRESNEL.
// Every combination compiles; an option whose prerequisite is missing is a no-op.
//
// Test-only switches (never in variants.yaml; `tidepool stability` uses them to measure what each
// numerical guard changes, docs/HARD_CASES.md): TP_NO_COS_CLAMP, TP_NO_NORMAL_FLOOR,
// TP_NO_EYE_FLOOR, TP_NO_EYE_SCALING each remove one guard; TP_FORCE_MEDIUMP takes the path of
// hardware without fragment highp. TP_OUTPUT_REFRACTION outputs the refracted colour after the
// depth optics, so tests can check extinction against its formula.
// water_uniform.fsh is the same shader with uniform bools; keep the two in step.

precision mediump float;

// ---- Feature dependencies (water.vsh repeats the part that decides varyings; keep in step) ----
#if defined(ENABLE_SCALE_DISTORTION) && !defined(ENABLE_DISTORTION)
#undef ENABLE_SCALE_DISTORTION
#endif
#if defined(ENABLE_FRESNEL) && !defined(ENABLE_REFRACTION)
#undef ENABLE_FRESNEL
#endif
#if defined(FRESNEL_EXACT) && !defined(ENABLE_FRESNEL)
#undef FRESNEL_EXACT
#endif
#if defined(NORMALISE_CUBEMAP) && !defined(ENABLE_FRESNEL)
#undef NORMALISE_CUBEMAP
#endif
// Water colour and alpha blending are the cheap stand-ins for refraction, not additions to it.
#if defined(ENABLE_WATER_COLOUR) && defined(ENABLE_REFRACTION)
#undef ENABLE_WATER_COLOUR
#endif
#if defined(ENABLE_ALPHA_BLEND) && defined(ENABLE_REFRACTION)
#undef ENABLE_ALPHA_BLEND
#endif
#if defined(ENABLE_EXTINCTION) && !defined(ENABLE_REFRACTION)
#undef ENABLE_EXTINCTION
#endif
#if defined(ENABLE_SHORE_FOAM) && !defined(ENABLE_REFRACTION)
#undef ENABLE_SHORE_FOAM
#endif
#if defined(ENABLE_SOFT_SHORE) && !defined(ENABLE_REFRACTION)
#undef ENABLE_SOFT_SHORE
#endif
#if defined(ENABLE_SUN_SPECULAR) && !defined(ENABLE_FRESNEL)
#undef ENABLE_SUN_SPECULAR
#endif
#if defined(REFLECTION_CUBEMAP) && defined(REFLECTION_FOURIER)
#error "REFLECTION_CUBEMAP and REFLECTION_FOURIER are values of one axis: define at most one"
#endif
#if defined(REFLECTION_CUBEMAP) || defined(REFLECTION_FOURIER)
#define REFLECTS_SKY_DIRECTION
#endif
// (GLSL ES 1.00 has no line continuation, hence one #if per line.)
#if defined(ENABLE_SCALE_DISTORTION) || defined(ENABLE_FRESNEL) || defined(ENABLE_FOG)
#define NEEDS_EYE_VECTOR
#endif
#if defined(REFLECTS_SKY_DIRECTION) || defined(ENABLE_EXTINCTION)
#define NEEDS_EYE_VECTOR
#endif
#if defined(ENABLE_SUN_SPECULAR)
#define NEEDS_EYE_VECTOR
#endif
#if defined(ENABLE_SCALE_DISTORTION) || defined(ENABLE_FOG)
#define NEEDS_EYE_DISTANCE
#endif
// The unit water-to-eye direction and the surface normal.
#if defined(ENABLE_FRESNEL) || defined(REFLECTS_SKY_DIRECTION) || defined(ENABLE_EXTINCTION)
#define NEEDS_EYE_DIRECTION
#endif
#if defined(ENABLE_EXTINCTION) || defined(ENABLE_SHORE_FOAM) || defined(ENABLE_SOFT_SHORE)
#define NEEDS_WATER_DEPTH
#endif
// A unit surface normal: the glare and the exact Fresnel reference.
#if defined(ENABLE_SUN_SPECULAR) || defined(FRESNEL_EXACT)
#define NEEDS_UNIT_NORMAL
#endif

// highp is optional in GLSL ES 1.00 fragment shaders; where it is missing, the eye vector and bump
// coordinates fall back to mediump. The eye-vector scaling below keeps lengths and directions
// right in fp16; what stays lost is bump-coordinate resolution on water more than ~1000 units
// away (fp16 spacing 0.5 at |coord| >= 1024), where the mipmapped normal map is a blur anyway.
#if defined(GL_FRAGMENT_PRECISION_HIGH) && !defined(TP_FORCE_MEDIUMP)
#define HIGHP_OR_MEDIUMP highp
#else
#define HIGHP_OR_MEDIUMP mediump
#endif

// Largest distortion factor (texture units per unit of bump normal): with normals' horizontal
// parts up to 0.5, offsets up to 8 textures, far past the edge any lookup clamps to.
const mediump float cMaxDistortion = 16.0;
// Reflection share of the constant reflection/refraction mix (whitepaper demo).
const mediump float cReflectionShare = 0.4;
// Alpha under ENABLE_ALPHA_BLEND: 40% of the scene below shows through.
const mediump float cBlendAlpha = 0.6;
// Smallest eye distance divided by; the camera can sit on the water plane.
// 1e-3 is a normal fp16 number (the smallest is 6.1e-5).
const HIGHP_OR_MEDIUMP float cMinEyeDistance = 1e-3;

#ifndef REFLECTS_SKY_DIRECTION
uniform sampler2D ReflectionTex;
#endif
uniform mediump vec2 RcpWindowSize;

#if defined(ENABLE_DISTORTION) || defined(ENABLE_SHORE_FOAM)
uniform sampler2D NormalTex;
#endif

#ifdef ENABLE_DISTORTION
uniform mediump float WaveDistortion;
varying HIGHP_OR_MEDIUMP vec2 BumpCoord0;
varying HIGHP_OR_MEDIUMP vec2 BumpCoord1;
#endif

#ifdef NEEDS_EYE_VECTOR
varying HIGHP_OR_MEDIUMP vec3 EyeVector;
#endif

#ifdef ENABLE_REFRACTION
uniform sampler2D RefractionTex;
#endif

#ifdef NORMALISE_CUBEMAP
uniform samplerCube NormalisationCubeMap;
#endif

#ifdef ENABLE_WATER_COLOUR
uniform lowp vec4 WaterColour;
#endif

#ifdef ENABLE_FOG
uniform lowp vec3 FogColour;
uniform mediump float RcpMaxFogDepth;
#endif

#ifdef REFLECTS_SKY_DIRECTION
uniform samplerCube SkyboxTex;
#ifdef ENABLE_FOG
// sin(10 degrees): as in skybox.fsh, whose horizon fog the planar reflection shows.
const mediump float cSinFogElevation = 0.173648;
#endif
#endif

#ifdef REFLECTION_FOURIER
uniform lowp vec3 TerrainReflectionColour;
varying mediump vec4 FourierCoefs0;
varying mediump vec4 FourierCoefs1;
// Half-width (radians) of the soft edge between reflected terrain and sky.
const mediump float cFourierEdge = 0.02;
#endif

#ifdef NEEDS_WATER_DEPTH
uniform mediump float MaxWaterDepth;
#endif

#ifdef ENABLE_EXTINCTION
uniform mediump vec3 Extinction;     // depth (world units) at which each channel is gone
uniform mediump float Visibility;    // path length (world units) at which the water is opaque
uniform lowp vec3 SurfaceColour;
uniform lowp vec3 DepthColour;
// Floor under the cosine of the view angle: the path length is at most 20 times the depth.
const mediump float cMinViewCos = 0.05;
// Floor under Visibility and Extinction (world units), a normal fp16 number.
const mediump float cMinOpticalLength = 1e-3;
#endif

#ifdef ENABLE_SHORE_FOAM
uniform lowp vec3 FoamColour;
uniform mediump vec2 FoamDepth;      // (full up to, gone at), world units
varying HIGHP_OR_MEDIUMP vec2 FoamCoord;
#endif

#ifdef ENABLE_SOFT_SHORE
uniform mediump float ShoreHardness; // 1 / the depth over which the shore blends in
#endif

#ifdef ENABLE_SUN_SPECULAR
uniform mediump vec3 SunDirection;   // unit vector towards the sun
uniform lowp vec3 SunColour;
uniform mediump float Shininess;     // seed: 0.5 to 0.7
#endif

#ifdef ENABLE_FRESNEL
#ifdef FRESNEL_EXACT
// Unpolarised reflectance of light arriving from air onto water, the mean of the s and p
// reflectances from the Fresnel equations. cosIncidence must already lie in [0, 1].
mediump float fresnelReflectance(mediump float cosIncidence)
{
    const mediump float n1 = 1.000293; // air
    const mediump float n2 = 1.333333; // water
    // Snell: sin^2(t) = (n1/n2)^2 sin^2(i). From air into water it never reaches 1, but clamping
    // 1 - sin^2(t) at 0 makes total internal reflection come out as cosT = 0, which gives
    // Rs = Rp = 1 below: the correct limit, with no NaN from sqrt of a negative number.
    mediump float eta = n1 / n2;
    mediump float sinT2 = eta * eta * (1.0 - cosIncidence * cosIncidence);
    mediump float cosT = sqrt(max(1.0 - sinT2, 0.0));
    // Both denominators are sums of non-negative terms; they vanish only at cosI = cosT = 0,
    // which the floor keeps from becoming 0/0 (1e-4 is representable in mediump).
    mediump float rs = (n1 * cosIncidence - n2 * cosT) / max(n1 * cosIncidence + n2 * cosT, 1e-4);
    mediump float rp = (n1 * cosT - n2 * cosIncidence) / max(n1 * cosT + n2 * cosIncidence, 1e-4);
    return 0.5 * (rs * rs + rp * rp);
}
#else
// Schlick's approximation, F = R0 + (1 - R0)(1 - cos)^5, with R0 = ((n1 - n2) / (n1 + n2))^2
// for air (1.000293) and water (1.333333). cosIncidence must already lie in [0, 1].
mediump float fresnelReflectance(mediump float cosIncidence)
{
    const mediump float r0 = 0.02037;
    // The fifth power by multiplication: exact, cheaper than pow(), defined for a base of 0.
    mediump float m = 1.0 - cosIncidence;
    mediump float m2 = m * m;
    return r0 + (1.0 - r0) * (m2 * m2 * m);
}
#endif
#endif

#ifdef REFLECTION_FOURIER
// The terrain's elevation angle in the horizontal direction `azimuth` = (cos t, sin t), the
// seed's eight-term series a0 + a1 cos t + b1 sin t + a2 cos 2t + b2 sin 2t + a3 cos 3t
// + b3 sin 3t + a4 cos 4t. The multiple angles come from the angle-addition formulas instead of
// the seed's atan2 and four sincos: the trigonometric substitution it names as the way to cut
// its ~64 instruction slots.
mediump float terrainElevation(mediump vec2 azimuth)
{
    mediump float c1 = azimuth.x;
    mediump float s1 = azimuth.y;
    mediump float c2 = c1 * c1 - s1 * s1;
    mediump float s2 = 2.0 * s1 * c1;
    mediump float c3 = c2 * c1 - s2 * s1;
    mediump float s3 = s2 * c1 + c2 * s1;
    mediump float c4 = c2 * c2 - s2 * s2;
    return FourierCoefs0.x + FourierCoefs0.y * c1 + FourierCoefs0.z * s1
         + FourierCoefs0.w * c2 + FourierCoefs1.x * s2 + FourierCoefs1.y * c3
         + FourierCoefs1.z * s3 + FourierCoefs1.w * c4;
}
#endif

void main()
{
    // Pixel position in the target the water is drawn into; the reflection and refraction passes
    // share the screen layout, so this is also where the mirrored/refracted scene lies.
    mediump vec2 screenCoord = gl_FragCoord.xy * RcpWindowSize;

#ifdef NEEDS_EYE_VECTOR
#ifdef TP_NO_EYE_SCALING
    HIGHP_OR_MEDIUMP float eyeScale = 1.0;
    HIGHP_OR_MEDIUMP vec3 eyeScaled = EyeVector;
#else
    // Divided by its largest component before squaring: |EyeVector|^2 overflows fp16 (65504)
    // beyond 256 units and loses precision below 0.01, whereas the scaled square lies in [1, 3]
    // (less only nearer than cMinEyeDistance). Costs three abs, two max and a divide.
    HIGHP_OR_MEDIUMP float eyeScale = max(max(abs(EyeVector.x), abs(EyeVector.y)),
                                          max(abs(EyeVector.z), cMinEyeDistance));
    HIGHP_OR_MEDIUMP vec3 eyeScaled = EyeVector / eyeScale;
#endif
    HIGHP_OR_MEDIUMP float eyeScaledLength2 = dot(eyeScaled, eyeScaled);
#endif

#ifdef NEEDS_EYE_DISTANCE
#ifdef TP_NO_EYE_FLOOR
    HIGHP_OR_MEDIUMP float eyeDistance = eyeScale * sqrt(eyeScaledLength2);
#else
    // Floored once here, so both the distortion divide and fog can use it: the camera can sit
    // on the water plane.
    HIGHP_OR_MEDIUMP float eyeDistance = max(eyeScale * sqrt(eyeScaledLength2), cMinEyeDistance);
#endif
#endif

#ifdef ENABLE_DISTORTION
    // The map is z-major (z is "up"). As in the demo, the two stored texels are added and 1
    // subtracted: (n0 * 0.5 + 0.5) + (n1 * 0.5 + 0.5) - 1 = (n0 + n1) / 2, the mean of the two
    // layers' normals, in one add and one subtract. Swizzled to world (x, z, y); not normalised.
    mediump vec3 bump = texture2D(NormalTex, BumpCoord0).rgb
                      + texture2D(NormalTex, BumpCoord1).rgb - 1.0;
    mediump vec3 bumpNormal = bump.xzy;

    mediump float distortion = WaveDistortion;
#ifdef ENABLE_SCALE_DISTORTION
    // The same ripple covers fewer pixels further away, so shrink its offset with distance.
    // Capped: in texture units an offset past the texture's edge only clamps to it, and the
    // demo's 100 over an eye distance below 100 / 65504 overflows mediump (Inf x 0 = NaN for a
    // flat bump). min() of Inf is the cap, so the cap also catches the overflow itself.
    distortion = min(WaveDistortion / eyeDistance, cMaxDistortion);
#endif
    // Subtracted in texture units, as in the whitepaper demo (WaveDistortion 100, scaled), so
    // the offset is the same share of the picture at any target size.
    screenCoord -= bumpNormal.xz * distortion;
#endif

#ifdef NEEDS_EYE_DIRECTION
#ifdef NORMALISE_CUBEMAP
    // The cube map stores normalize(dir) * 0.5 + 0.5, so a lookup replaces the rsqrt.
    HIGHP_OR_MEDIUMP vec3 eyeDirection =
            textureCube(NormalisationCubeMap, EyeVector).rgb * 2.0 - 1.0;
#elif defined(TP_NO_EYE_FLOOR)
    HIGHP_OR_MEDIUMP vec3 eyeDirection = eyeScaled * inversesqrt(eyeScaledLength2);
#else
    // normalize() with a floor under the squared length, so a zero vector cannot give NaN
    // (1e-4 is representable in mediump; the scaled square is >= 1 unless the eye is nearer
    // than cMinEyeDistance).
    HIGHP_OR_MEDIUMP vec3 eyeDirection = eyeScaled * inversesqrt(max(eyeScaledLength2, 1e-4));
#endif
#if !defined(ENABLE_DISTORTION)
    mediump vec3 normal = vec3(0.0, 1.0, 0.0);
#elif !defined(NEEDS_UNIT_NORMAL)
    // Schlick's Fresnel takes the accumulated normal as it is, as the whitepaper's demo did
    // ("the assumption is made that the accumulated normal ... is already normalised"): the mean
    // of two unit normals tilted at most 27 degrees is at least 0.89 long.
    mediump vec3 normal = bumpNormal;
#elif defined(TP_NO_NORMAL_FLOOR)
    mediump vec3 normal = normalize(bumpNormal);
#else
    // The sun's glare and the exact Fresnel reference need a unit normal:
    // normalised with a floor rather than normalize(), which is NaN for a zero vector (a float
    // normal map could hold exactly 0.5 grey; 1e-4 is representable in mediump).
    mediump vec3 normal = bumpNormal * inversesqrt(max(dot(bumpNormal, bumpNormal), 1e-4));
#endif
#ifdef TP_NO_COS_CLAMP
    mediump float cosIncidence = dot(normal, eyeDirection);
#else
    // Clamped: the cube map's 8-bit vectors and back-facing bump normals can push the dot
    // product outside [0, 1], and 1 - cos must stay in [0, 1] for the fifth power (pow() of a
    // negative base is undefined in GLSL) and for a reflectance in [0, 1].
    mediump float cosIncidence = clamp(dot(normal, eyeDirection), 0.0, 1.0);
#endif
#endif

#ifdef REFLECTS_SKY_DIRECTION
    // The view ray reflected about the normal: reflect(-eyeDirection, normal). A back-facing
    // bump normal can send it below the horizon; mirrored back up (its length stays 1), since
    // the reflection of a ray leaving the water surface cannot point into the water.
#ifdef ENABLE_DISTORTION
    // Perturbed by the planar lookup's convention, so the techniques compare at one ripple
    // strength: the normal's tilt (its horizontal part over its vertical) is the offset the
    // planar reflection applies, bump x distortion (texture units), and scales with the eye
    // distance as it does. Clamped at a tilt of 8 (83 degrees) so that a distortion divided by
    // the floored eye distance cannot overflow mediump when squared.
    mediump vec2 tilt = clamp(bumpNormal.xz * distortion, -8.0, 8.0);
    mediump vec3 skyNormal = vec3(tilt.x, 1.0, tilt.y) * inversesqrt(1.0 + dot(tilt, tilt));
#else
    mediump vec3 skyNormal = vec3(0.0, 1.0, 0.0);
#endif
    mediump vec3 reflected = 2.0 * dot(skyNormal, eyeDirection) * skyNormal - eyeDirection;
    reflected.y = abs(reflected.y);
    mediump vec3 colour = textureCube(SkyboxTex, reflected).rgb;
#ifdef ENABLE_FOG
    // The horizon fog skybox.fsh gives the sky, which the planar reflection shows mirrored.
    colour = mix(colour, FogColour, clamp(1.0 - reflected.y / cSinFogElevation, 0.0, 1.0));
#endif
#ifdef REFLECTION_FOURIER
    // The reflected ray's horizontal direction, normalised with a floor: straight up it has
    // none, and there the series' value is a0, below the ray's elevation of ~90 degrees for any
    // terrain. 1e-4 is representable in mediump.
    mediump vec2 horizontal = reflected.xz;
    mediump vec2 azimuth = horizontal * inversesqrt(max(dot(horizontal, horizontal), 1e-4));
    mediump float elevation = asin(clamp(reflected.y, 0.0, 1.0));
    mediump float terrain = smoothstep(-cFourierEdge, cFourierEdge,
                                       terrainElevation(azimuth) - elevation);
    colour = mix(colour, TerrainReflectionColour, terrain);
#endif
#else
    mediump vec3 colour = texture2D(ReflectionTex, screenCoord).rgb;
#endif

#ifdef ENABLE_REFRACTION
    mediump vec4 refracted = texture2D(RefractionTex, screenCoord);
    mediump vec3 refraction = refracted.rgb;
#ifdef NEEDS_WATER_DEPTH
    // The refraction pass stored sqrt(D / MaxWaterDepth): finer steps in shallow water, where
    // the shore effects change fastest.
    mediump float waterDepth = refracted.a * refracted.a * MaxWaterDepth;
#endif
#ifdef ENABLE_EXTINCTION
    // Horizontal visibility first (the water's own colour along the path), then extinction with
    // depth, channel by channel: red is gone at Extinction.r, blue only at Extinction.b.
    // The divisors are floored: a visibility or extinction of 0 ("opaque at once") would give
    // 0/0 = NaN at the water line; floored, 0 depth stays clear and any depth above 1e-3 is
    // opaque, as the CPU reference (WaterMath.h, ExtinctionColour) has it.
    mediump float pathLength = waterDepth / max(eyeDirection.y, cMinViewCos);
    refraction = mix(refraction, SurfaceColour,
                     clamp(pathLength / max(Visibility, cMinOpticalLength), 0.0, 1.0));
    refraction = mix(refraction, DepthColour,
                     clamp(vec3(waterDepth) / max(Extinction, vec3(cMinOpticalLength)), 0.0, 1.0));
#endif
#ifdef TP_OUTPUT_REFRACTION
    gl_FragColor = vec4(refraction, 1.0);
    return;
#endif
    mediump float reflectance = cReflectionShare;
#ifdef ENABLE_FRESNEL
    reflectance = fresnelReflectance(cosIncidence);
#endif
    colour = mix(refraction, colour, reflectance);

#ifdef ENABLE_SUN_SPECULAR
    // The seed's glare: the eye direction mirrored about the normal against the sun, raised to
    // the 512th power, weighted by (1 - Fresnel) and the sun's height. Clamped: the boost for
    // shininess above 0.05 takes the sum past 1.
    // pow(dotSpec, 512) with dotSpec = dot(m, s) * 0.5 + 0.5 bands into rings at mediump: near 1
    // fp16's spacing is 2^-11, and one step moves the 512th power by 22%. For unit m and s,
    // 1 - dotSpec = |m - s|^2 / 4 keeps full relative precision near the highlight, and
    // (1 - u)^512 = exp2(512 log2(1 - u)) ~ exp2(-738.65 (u + u^2 / 2)) (512 / ln 2 = 738.65; the
    // dropped u^3 / 3 moves the exponent by < 3e-4 wherever the power exceeds 1/255).
    mediump vec3 mirrorEye = 2.0 * dot(eyeDirection, normal) * normal - eyeDirection;
    mediump vec3 toSun = mirrorEye - SunDirection;
    mediump float u = min(dot(toSun, toSun) * 0.25, 1.0);
    mediump float glare = exp2(-738.65 * (u + 0.5 * u * u));
    mediump float specular = (1.0 - reflectance) * clamp(SunDirection.y, 0.0, 1.0)
                           * glare * (Shininess * 1.8 + 0.2);
    specular += specular * 25.0 * clamp(Shininess - 0.05, 0.0, 1.0);
    colour = min(colour + specular * SunColour, vec3(1.0));
#endif

#ifdef ENABLE_SHORE_FOAM
    // Full up to FoamDepth.x, gone at FoamDepth.y; the normal map's x slope, thresholded, breaks
    // it into patches.
    mediump float foamPattern = smoothstep(0.45, 0.75, texture2D(NormalTex, FoamCoord).r);
    mediump float foam = (1.0 - smoothstep(FoamDepth.x, FoamDepth.y, waterDepth)) * foamPattern;
    colour = mix(colour, FoamColour, foam);
#endif

#ifdef ENABLE_SOFT_SHORE
    colour = mix(refraction, colour, clamp(waterDepth * ShoreHardness, 0.0, 1.0));
#endif
#endif

#ifdef ENABLE_WATER_COLOUR
    colour = mix(colour, WaterColour.rgb, WaterColour.a);
#endif

#ifdef ENABLE_FOG
    colour = mix(colour, FogColour, clamp(eyeDistance * RcpMaxFogDepth, 0.0, 1.0));
#endif

#ifdef ENABLE_ALPHA_BLEND
    gl_FragColor = vec4(colour, cBlendAlpha);
#else
    gl_FragColor = vec4(colour, 1.0);
#endif
}
