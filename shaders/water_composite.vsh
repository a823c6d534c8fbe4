#version 100
// Low-resolution water apply pass, vertex stage: draws the water polygon again at full
// resolution. Interface: shaders/INTERFACE.md ("water_composite").
//
// No defines. The fragment stage finds its texel from gl_FragCoord, so no varyings are needed.

attribute highp vec3 inVertex;

uniform highp mat4 ModelViewProjMatrix;

void main()
{
    gl_Position = ModelViewProjMatrix * vec4(inVertex, 1.0);
}
