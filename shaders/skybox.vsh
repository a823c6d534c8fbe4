#version 100
// Sky box, vertex stage: a unit cube around the camera, pinned to the far plane.
// Interface: shaders/INTERFACE.md ("skybox").
//
// Defines: ENABLE_FOG and CLIP_DISCARD only change the fragment stage (see skybox.fsh); this
// stage always passes the cube-map direction on.

attribute highp vec3 inVertex;

// View rotation and projection only: the sky must not move with the camera's translation.
uniform highp mat4 ModelViewProjMatrix;

// The cube vertex itself is the lookup direction. Not normalised here: the direction must
// interpolate linearly across each face; the fragment stage normalises where it needs a unit
// vector (a cube-map lookup does not).
varying mediump vec3 SkyDirection;

void main()
{
    SkyDirection = inVertex;
    // z = w puts every sky fragment at depth 1.0, behind all scene geometry, whatever the cube's
    // size relative to the near and far planes.
    gl_Position = (ModelViewProjMatrix * vec4(inVertex, 1.0)).xyww;
}
