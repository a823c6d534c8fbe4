#version 100
// Water surface, fragment stage: a screen-space lookup into the reflection (and refraction) pass
// textures, perturbed by animated bump layers. Interface: shaders/INTERFACE.md ("water").
// Costs quoted are the whitepaper's (PowerVR SGX class); this renderer measures its own.
//
// Defines:
//   ENABLE_DISTORTION        Ripples: two NormalTex samples offset the screen-space lookup.
//                            Buys a moving surface; costs two dependent texture reads.
//   ENABLE_SCALE_DISTORTION  Divides the offset by the eye distance so far water does not shimmer
//                            more than near water. Needs ENABLE_DISTORTION. Costs a length and a
//                            divide (whitepaper: <1%).
//   ENABLE_REFRACTION        Mixes in RefractionTex (0.4 reflection). Buys visible depths; costs a
//                            whole extra render pass plus a texture read (whitepaper: -60%).
//   ENABLE_FRESNEL           Schlick's angle-dependent mix instead of the constant 0.4.
//                            Needs ENABLE_REFRACTION. Costs a normalisation and a few multiplies
//                            (whitepaper: -22%).
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
// Every combination compiles; an option whose prerequisite is missing is a no-op.
//
// Test-only switches (never in variants.yaml; `tidepool stability` uses them to measure what each
// numerical guard changes, docs/HARD_CASES.md): TP_NO_COS_CLAMP, TP_NO_NORMAL_FLOOR,
// TP_NO_EYE_FLOOR, TP_NO_EYE_SCALING each remove one guard; TP_FORCE_MEDIUMP takes the path of
// hardware without fragment highp.
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
#if defined(ENABLE_SCALE_DISTORTION) || defined(ENABLE_FRESNEL) || defined(ENABLE_FOG)
#define NEEDS_EYE_VECTOR
#endif
#if defined(ENABLE_SCALE_DISTORTION) || defined(ENABLE_FOG)
#define NEEDS_EYE_DISTANCE
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

// Reflection share of the constant reflection/refraction mix (whitepaper demo).
const mediump float cReflectionShare = 0.4;
// Alpha under ENABLE_ALPHA_BLEND: 40% of the scene below shows through.
const mediump float cBlendAlpha = 0.6;
// Smallest eye distance divided by; the camera can sit on the water plane.
// 1e-3 is a normal fp16 number (the smallest is 6.1e-5).
const HIGHP_OR_MEDIUMP float cMinEyeDistance = 1e-3;

uniform sampler2D ReflectionTex;
uniform mediump vec2 RcpWindowSize;

#ifdef ENABLE_DISTORTION
uniform sampler2D NormalTex;
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
    // The map is z-major (z is "up"): sum the two layers in texture space, then swizzle to world
    // (x, z, y). The sum is not normalised: the offset wants its length, Fresnel normalises it.
    mediump vec3 bump = (texture2D(NormalTex, BumpCoord0).rgb * 2.0 - 1.0)
                      + (texture2D(NormalTex, BumpCoord1).rgb * 2.0 - 1.0);
    mediump vec3 bumpNormal = bump.xzy;

    mediump float distortion = WaveDistortion;
#ifdef ENABLE_SCALE_DISTORTION
    // The same ripple covers fewer pixels further away, so shrink its offset with distance.
    distortion = WaveDistortion / eyeDistance;
#endif
    // Subtracted, as in the whitepaper demo; WaveDistortion is in pixels, hence RcpWindowSize.
    screenCoord -= bumpNormal.xz * distortion * RcpWindowSize;
#endif

    mediump vec3 colour = texture2D(ReflectionTex, screenCoord).rgb;

#ifdef ENABLE_REFRACTION
    mediump vec3 refraction = texture2D(RefractionTex, screenCoord).rgb;
    mediump float reflectance = cReflectionShare;
#ifdef ENABLE_FRESNEL
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
#elif defined(TP_NO_NORMAL_FLOOR)
    mediump vec3 normal = normalize(bumpNormal);
#else
    // The sum of two bump layers is not unit length (the whitepaper assumes it is): normalised
    // with a floor rather than normalize(), which is NaN for a zero vector (a float normal map
    // could hold exactly 0.5 grey; 1e-4 is representable in mediump).
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
    reflectance = fresnelReflectance(cosIncidence);
#endif
    colour = mix(refraction, colour, reflectance);
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
