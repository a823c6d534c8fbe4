#version 100
// Sky box, fragment stage. Interface: shaders/INTERFACE.md ("skybox").
//
// Defines:
//   ENABLE_FOG    Fades the sky into FogColour towards the horizon (fully fogged at and below
//                 0 degrees elevation, clear from 10 degrees up), so it meets the fogged water
//                 without a seam. Costs a normalisation and a mix.
//   CLIP_DISCARD  Discards sky below ClipPlane, the fallback for reflection/refraction passes that
//                 do not clip with an oblique projection. Costs a normalisation, a dot product
//                 and a discard, which disables early depth tests on tile-based GPUs; the
//                 whitepaper recommends the projection matrix method instead.

precision mediump float;

// highp is optional in GLSL ES 1.00 fragment shaders; without it this falls back to mediump
// (docs/HARD_CASES.md, "Precision"). TP_FORCE_MEDIUMP takes that path for tests.
#if defined(GL_FRAGMENT_PRECISION_HIGH) && !defined(TP_FORCE_MEDIUMP)
#define HIGHP_OR_MEDIUMP highp
#else
#define HIGHP_OR_MEDIUMP mediump
#endif

uniform samplerCube SkyboxTex;

varying mediump vec3 SkyDirection;

#ifdef ENABLE_FOG
uniform lowp vec3 FogColour;

// sin(10 degrees): the elevation at which the horizon fog has fully cleared.
const mediump float cSinFogElevation = 0.173648;
#endif

#ifdef CLIP_DISCARD
uniform HIGHP_OR_MEDIUMP vec3 EyePosition;
uniform HIGHP_OR_MEDIUMP vec4 ClipPlane;

// Distance at which the sky is taken to lie when clipping it against a world-space plane.
const HIGHP_OR_MEDIUMP float cSkyDistance = 1000.0;
#endif

void main()
{
#if defined(ENABLE_FOG) || defined(CLIP_DISCARD)
    // The interpolated cube-face point is not unit length. Every point on the faces is at least
    // the cube's half-size from its centre, so this never normalises a zero vector.
    HIGHP_OR_MEDIUMP vec3 direction = normalize(SkyDirection);
#endif

#ifdef CLIP_DISCARD
    HIGHP_OR_MEDIUMP vec3 skyPoint = EyePosition + direction * cSkyDistance;
    if (dot(ClipPlane, vec4(skyPoint, 1.0)) < 0.0) {
        discard;
    }
#endif

    mediump vec3 colour = textureCube(SkyboxTex, SkyDirection).rgb;

#ifdef ENABLE_FOG
    // Elevation measured by its sine (direction.y), which is close to linear in the angle over
    // 0..10 degrees and avoids asin().
    mediump float fog = clamp(1.0 - direction.y / cSinFogElevation, 0.0, 1.0);
    colour = mix(colour, FogColour, fog);
#endif

    gl_FragColor = vec4(colour, 1.0);
}
