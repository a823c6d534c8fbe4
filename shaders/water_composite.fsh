#version 100
// Low-resolution water apply pass, fragment stage: copies the water image, rendered by the water
// program into a small texture, onto the full-resolution water polygon. Interface:
// shaders/INTERFACE.md ("water_composite"). The whitepaper measured ~18% faster at 640x480 with a
// 256x256 water texture: the expensive water shader runs on fewer fragments, and this pass is one
// bilinear texture read per fragment; the cost is a blurrier surface.
//
// No defines.

precision mediump float;

uniform sampler2D WaterTex;
uniform mediump vec2 RcpWindowSize;

void main()
{
    // The small texture covers the same screen area, so the full-resolution screen coordinate
    // maps onto it directly. Alpha is passed through: the water program may have written 0.6
    // (ENABLE_ALPHA_BLEND) for this pass to blend with.
    gl_FragColor = texture2D(WaterTex, gl_FragCoord.xy * RcpWindowSize);
}
