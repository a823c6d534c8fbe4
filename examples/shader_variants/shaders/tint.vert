#version 100
// Textured quad. Defines:
//   FOG   passes the eye distance on for distance fog (one varying, one length()).
attribute vec4 position;
attribute vec2 uv;
uniform mat4 mvp;
varying vec2 v_uv;
#ifdef FOG
varying float v_distance;
#endif
void main() {
    v_uv = uv;
    gl_Position = mvp * position;
#ifdef FOG
    v_distance = length(gl_Position.xyz);
#endif
}
