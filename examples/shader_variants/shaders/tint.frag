#version 100
// Textured quad. Defines:
//   TINT      multiplies by a uniform colour (one multiply).
//   FOG       linear distance fog (a mix; needs the vertex stage's FOG varying).
//   FOG_EXP2  squared-exponential fog instead of linear (an exp; needs FOG).
precision mediump float;
uniform sampler2D image;
varying vec2 v_uv;
#ifdef TINT
uniform vec4 tint;
#endif
#ifdef FOG
uniform vec4 fog_colour;
uniform float fog_density;
varying float v_distance;
#endif
void main() {
    vec4 colour = texture2D(image, v_uv);
#ifdef TINT
    colour *= tint;
#endif
#ifdef FOG
#ifdef FOG_EXP2
    float d = fog_density * v_distance;
    float visibility = exp(-d * d);
#else
    float visibility = clamp(1.0 - fog_density * v_distance, 0.0, 1.0);
#endif
    colour = mix(fog_colour, colour, visibility);
#endif
    gl_FragColor = colour;
}
