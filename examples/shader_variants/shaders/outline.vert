#version 100
// Outline of a mesh. Defines:
//   THICK  pushes vertices out along their normal (one multiply-add).
attribute vec4 position;
attribute vec3 normal;
uniform mat4 mvp;
uniform float width;
void main() {
    vec4 p = position;
#ifdef THICK
    p.xyz += normal * width;
#endif
    gl_Position = mvp * p;
}
