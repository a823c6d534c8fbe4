#version 100
// Terrain and objects, fragment stage. Interface: shaders/INTERFACE.md ("model").
//
// Defines:
//   ENABLE_LIGHTING   Nothing here: lighting is per vertex (see model.vsh).
//   ENABLE_FOG_DEPTH  Underwater depth fog: fades towards FogColour (the water colour) with depth
//                     below the water plane, so submerged terrain grows murky in the refraction
//                     pass. Costs a multiply, a clamp and a mix (whitepaper: fog overall +3.5%
//                     when disabled).
//   ENABLE_DEPTH_ALPHA  Writes the water depth of the fragment into alpha as
//                     sqrt(clamp(depth / MaxWaterDepth, 0, 1)), for the depth-based optics of
//                     water.fsh (ENABLE_EXTINCTION, ENABLE_SHORE_FOAM, ENABLE_SOFT_SHORE), which
//                     read it from the refraction pass. The square root spends the 8 bits on
//                     shallow water, where the shore effects change fastest. Costs a sqrt.
//   CLIP_DISCARD      Discards fragments on the negative side of ClipPlane, the fallback for
//                     reflection/refraction passes that do not clip with an oblique projection.
//                     Costs a discard, which disables early depth tests on tile-based GPUs; the
//                     whitepaper recommends the projection matrix method instead.

precision mediump float;

// highp is optional in GLSL ES 1.00 fragment shaders; without it this falls back to mediump
// (docs/HARD_CASES.md, "Precision"). TP_FORCE_MEDIUMP takes that path for tests.
#if defined(GL_FRAGMENT_PRECISION_HIGH) && !defined(TP_FORCE_MEDIUMP)
#define HIGHP_OR_MEDIUMP highp
#else
#define HIGHP_OR_MEDIUMP mediump
#endif

varying lowp vec3 Colour;

#ifdef ENABLE_FOG_DEPTH
uniform mediump float RcpMaxFogDepth;
uniform lowp vec3 FogColour;
#endif

#ifdef ENABLE_DEPTH_ALPHA
uniform mediump float RcpMaxWaterDepth;
#endif

#if defined(ENABLE_FOG_DEPTH) || defined(ENABLE_DEPTH_ALPHA)
varying mediump float WaterDepth;
#endif

#ifdef CLIP_DISCARD
varying HIGHP_OR_MEDIUMP float ClipDistance;
#endif

void main()
{
#ifdef CLIP_DISCARD
    if (ClipDistance < 0.0) {
        discard;
    }
#endif

    mediump vec3 colour = Colour;

#ifdef ENABLE_FOG_DEPTH
    // Above the water the depth is negative and the clamp leaves the colour unfogged.
    colour = mix(colour, FogColour, clamp(WaterDepth * RcpMaxFogDepth, 0.0, 1.0));
#endif

#ifdef ENABLE_DEPTH_ALPHA
    // Above the water (the clip offset's sliver) the depth is negative: stored as 0.
    gl_FragColor = vec4(colour, sqrt(clamp(WaterDepth * RcpMaxWaterDepth, 0.0, 1.0)));
#else
    gl_FragColor = vec4(colour, 1.0);
#endif
}
