#version 100
// Outline of a mesh: one flat colour. Defines: none.
precision mediump float;
uniform vec4 colour;
void main() {
    gl_FragColor = colour;
}
