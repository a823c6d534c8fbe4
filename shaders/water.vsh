#version 100
// Water surface, vertex stage: projects the water polygon and hands the fragment stage the
// per-vertex inputs of the enabled effects. Interface: shaders/INTERFACE.md ("water").
//
// Defines (the same set as water.fsh; this stage only needs to know which varyings to write):
//   ENABLE_DISTORTION        + two animated bump-map coordinates (2 x vec2 varying).
//   ENABLE_SCALE_DISTORTION  + eye vector varying (needs ENABLE_DISTORTION, inert without it).
//   ENABLE_REFRACTION        nothing here.
//   ENABLE_FRESNEL           + eye vector varying (needs ENABLE_REFRACTION, inert without it).
//   FRESNEL_EXACT, NORMALISE_CUBEMAP, ENABLE_WATER_COLOUR, ENABLE_ALPHA_BLEND: nothing here.
//   ENABLE_FOG               + eye vector varying.
//   REFLECTION_CUBEMAP       + eye vector varying (the view ray is reflected into the sky).
//   REFLECTION_FOURIER       + eye vector varying, + the vertex's Fourier coefficients of the
//                            terrain's elevation angle (two vec4 attributes passed through).
//   ENABLE_EXTINCTION        + eye vector varying (the path length through the water).
//   ENABLE_SUN_SPECULAR      + eye vector varying.
//   ENABLE_SHORE_FOAM        + a foam-pattern coordinate.
//   ENABLE_SOFT_SHORE        nothing here.
// Every combination compiles; the dependency block below turns an option whose prerequisite is
// missing into a no-op. water.fsh repeats it, so both stages agree on which varyings exist.

// ---- Feature dependencies (the varying-deciding part of water.fsh's block; keep in step) ----
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
#if defined(ENABLE_EXTINCTION) && !defined(ENABLE_REFRACTION)
#undef ENABLE_EXTINCTION
#endif
#if defined(ENABLE_SHORE_FOAM) && !defined(ENABLE_REFRACTION)
#undef ENABLE_SHORE_FOAM
#endif
#if defined(ENABLE_SUN_SPECULAR) && !defined(ENABLE_FRESNEL)
#undef ENABLE_SUN_SPECULAR
#endif
// (GLSL ES 1.00 has no line continuation, hence one #if per line.)
#if defined(ENABLE_SCALE_DISTORTION) || defined(ENABLE_FRESNEL) || defined(ENABLE_FOG)
#define NEEDS_EYE_VECTOR
#endif
#if defined(REFLECTION_CUBEMAP) || defined(REFLECTION_FOURIER)
#define NEEDS_EYE_VECTOR
#endif
#if defined(ENABLE_EXTINCTION) || defined(ENABLE_SUN_SPECULAR)
#define NEEDS_EYE_VECTOR
#endif

attribute highp vec3 inVertex;

#ifdef REFLECTION_FOURIER
// (a0, a1, b1, a2) and (b2, a3, b3, a4): the terrain's elevation angle around this vertex as a
// function of azimuth, computed on the CPU (runner/include/tidepool/runner/FourierReflection.h).
attribute mediump vec4 inFourier0;
attribute mediump vec4 inFourier1;

// Linear interpolation of coefficients is interpolation of the functions they describe.
varying mediump vec4 FourierCoefs0;
varying mediump vec4 FourierCoefs1;
#endif

#ifdef ENABLE_SHORE_FOAM
uniform mediump vec2 FoamScale;
uniform mediump vec2 BumpTranslation0;

// highp for the same reason as the bump coordinates below.
varying highp vec2 FoamCoord;
#endif

uniform highp mat4 ModelViewProjMatrix;

#ifdef ENABLE_DISTORTION
uniform mediump vec2 BumpScale0;
uniform mediump vec2 BumpScale1;
#ifndef ENABLE_SHORE_FOAM
uniform mediump vec2 BumpTranslation0;
#endif
uniform mediump vec2 BumpTranslation1;

// highp: the "infinite" water polygon reaches the far plane, so its bump coordinates grow large
// and mediump (11-bit mantissa) would quantise them into visible steps.
varying highp vec2 BumpCoord0;
varying highp vec2 BumpCoord1;
#endif

#ifdef NEEDS_EYE_VECTOR
uniform highp vec3 EyePosition;

// Water-to-eye vector, not normalised: it interpolates linearly, whereas a normalised vector
// would not, so the fragment stage normalises it (and takes its length) per fragment.
// highp: far vertices are thousands of units away and the fragment stage squares this.
varying highp vec3 EyeVector;
#endif

void main()
{
    gl_Position = ModelViewProjMatrix * vec4(inVertex, 1.0);

#ifdef ENABLE_DISTORTION
    // Two layers at different scales and speeds, so the ripples do not visibly slide in a line.
    BumpCoord0 = inVertex.xz * BumpScale0 + BumpTranslation0;
    BumpCoord1 = inVertex.xz * BumpScale1 + BumpTranslation1;
#endif

#ifdef NEEDS_EYE_VECTOR
    EyeVector = EyePosition - inVertex;
#endif

#ifdef REFLECTION_FOURIER
    FourierCoefs0 = inFourier0;
    FourierCoefs1 = inFourier1;
#endif

#ifdef ENABLE_SHORE_FOAM
    // The foam drifts with the first bump layer.
    FoamCoord = inVertex.xz * FoamScale + BumpTranslation0;
#endif
}
