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

// Reflection share of the constant reflection/refraction mix (whitepaper demo).
const mediump float cReflectionShare = 0.4;
// Alpha under ENABLE_ALPHA_BLEND: 40% of the scene below shows through.
const mediump float cBlendAlpha = 0.6;
// Smallest eye distance divided by; the camera can sit on the water plane.
const highp float cMinEyeDistance = 1e-3;

uniform sampler2D ReflectionTex;
uniform mediump vec2 RcpWindowSize;

#ifdef ENABLE_DISTORTION
uniform sampler2D NormalTex;
uniform mediump float WaveDistortion;
varying highp vec2 BumpCoord0;
varying highp vec2 BumpCoord1;
#endif

#ifdef NEEDS_EYE_VECTOR
varying highp vec3 EyeVector;
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

#ifdef NEEDS_EYE_DISTANCE
    // Floored once here, so both the distortion divide and fog can use it.
    highp float eyeDistance = max(length(EyeVector), cMinEyeDistance);
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
    highp vec3 eyeDirection = textureCube(NormalisationCubeMap, EyeVector).rgb * 2.0 - 1.0;
#else
    // normalize() with a floor under the squared length, so a zero vector cannot give NaN.
    highp vec3 eyeDirection = EyeVector * inversesqrt(max(dot(EyeVector, EyeVector), 1e-8));
#endif
#ifdef ENABLE_DISTORTION
    // inversesqrt with a floor rather than normalize(), which is NaN for a zero vector
    // (a float normal map could hold exactly 0.5 grey; 1e-4 is representable in mediump).
    mediump vec3 normal = bumpNormal * inversesqrt(max(dot(bumpNormal, bumpNormal), 1e-4));
#else
    mediump vec3 normal = vec3(0.0, 1.0, 0.0);
#endif
    // Clamped: the cube map's 8-bit vectors and back-facing bump normals can push the dot
    // product slightly outside [0, 1].
    mediump float cosIncidence = clamp(dot(normal, eyeDirection), 0.0, 1.0);
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
