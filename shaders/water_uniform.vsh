#version 100
// Water surface, vertex stage of the run-time-switched variant: water.vsh with every output
// always written. Interface: shaders/INTERFACE.md ("water_uniform").
//
// No defines. The features are uniform bools read by water_uniform.fsh only; this stage writes
// both bump coordinates and the eye vector unconditionally, since three vertex-shader outputs
// cost next to nothing next to a branch per decision and keep the two stages' varyings fixed.
// The arithmetic is water.vsh's, line for line, so both variants render the same image.

attribute highp vec3 inVertex;

uniform highp mat4 ModelViewProjMatrix;
uniform highp vec3 EyePosition;
uniform mediump vec2 BumpScale0;
uniform mediump vec2 BumpScale1;
uniform mediump vec2 BumpTranslation0;
uniform mediump vec2 BumpTranslation1;

// highp for the same reasons as in water.vsh: the water polygon reaches the far plane, so bump
// coordinates grow large and the fragment stage squares the eye vector.
varying highp vec2 BumpCoord0;
varying highp vec2 BumpCoord1;
// Water-to-eye vector, not normalised, because it must interpolate linearly.
varying highp vec3 EyeVector;

void main()
{
    gl_Position = ModelViewProjMatrix * vec4(inVertex, 1.0);

    BumpCoord0 = inVertex.xz * BumpScale0 + BumpTranslation0;
    BumpCoord1 = inVertex.xz * BumpScale1 + BumpTranslation1;

    EyeVector = EyePosition - inVertex;
}
