#version 100
// Water surface, fragment stage of the run-time-switched variant: the effects of water.fsh
// selected by uniform bools instead of #defines. Interface: shaders/INTERFACE.md
// ("water_uniform"). It exists to measure what the whitepaper's section 3.2 describes: a bool
// branch costs "at least an extra cycle for each decision point" that a #define variant saves.
//
// No defines. Uniform bools, one per define of water.fsh (see its header for what each buys):
//   bDistortion, bScaleDistortion (needs bDistortion), bRefraction, bFresnel (needs bRefraction),
//   bFresnelExact (needs bFresnel), bNormaliseCubemap (needs bFresnel), bWaterColour and
//   bAlphaBlend (both ignored with bRefraction), bFog.
// An option whose prerequisite is off is a no-op, exactly as in water.fsh. For the same settings
// this shader performs water.fsh's math in the same order, so both render the same image;
// keep the two in step.

precision mediump float;

const mediump float cReflectionShare = 0.4;
const mediump float cBlendAlpha = 0.6;
// highp is optional in GLSL ES 1.00 fragment shaders: the same mediump fallback as water.fsh.
#if defined(GL_FRAGMENT_PRECISION_HIGH) && !defined(TP_FORCE_MEDIUMP)
#define HIGHP_OR_MEDIUMP highp
#else
#define HIGHP_OR_MEDIUMP mediump
#endif

const HIGHP_OR_MEDIUMP float cMinEyeDistance = 1e-3;
const mediump float cMaxDistortion = 16.0;  // water.fsh says why

uniform bool bDistortion;
uniform bool bScaleDistortion;
uniform bool bRefraction;
uniform bool bFresnel;
uniform bool bFresnelExact;
uniform bool bNormaliseCubemap;
uniform bool bWaterColour;
uniform bool bAlphaBlend;
uniform bool bFog;

uniform sampler2D ReflectionTex;
uniform sampler2D RefractionTex;
uniform sampler2D NormalTex;
uniform samplerCube NormalisationCubeMap;
uniform mediump vec2 RcpWindowSize;
uniform mediump float WaveDistortion;
uniform lowp vec4 WaterColour;
uniform lowp vec3 FogColour;
uniform mediump float RcpMaxFogDepth;

varying HIGHP_OR_MEDIUMP vec2 BumpCoord0;
varying HIGHP_OR_MEDIUMP vec2 BumpCoord1;
varying HIGHP_OR_MEDIUMP vec3 EyeVector;

// Unpolarised air-to-water reflectance from the Fresnel equations; same as water.fsh
// (FRESNEL_EXACT), which explains the clamps. cosIncidence must already lie in [0, 1].
mediump float fresnelExact(mediump float cosIncidence)
{
    const mediump float n1 = 1.000293; // air
    const mediump float n2 = 1.333333; // water
    mediump float eta = n1 / n2;
    mediump float sinT2 = eta * eta * (1.0 - cosIncidence * cosIncidence);
    mediump float cosT = sqrt(max(1.0 - sinT2, 0.0));
    mediump float rs = (n1 * cosIncidence - n2 * cosT) / max(n1 * cosIncidence + n2 * cosT, 1e-4);
    mediump float rp = (n1 * cosT - n2 * cosIncidence) / max(n1 * cosT + n2 * cosIncidence, 1e-4);
    return 0.5 * (rs * rs + rp * rp);
}

// Schlick's approximation with R0 = 0.02037 (air 1.000293, water 1.333333); same as water.fsh.
mediump float fresnelSchlick(mediump float cosIncidence)
{
    const mediump float r0 = 0.02037;
    mediump float m = 1.0 - cosIncidence;
    mediump float m2 = m * m;
    return r0 + (1.0 - r0) * (m2 * m2 * m);
}

void main()
{
    // Resolve the dependencies between options, as the #if block at the top of water.fsh does.
    bool scaleDistortion = bDistortion && bScaleDistortion;
    bool fresnel = bRefraction && bFresnel;
    bool waterColour = bWaterColour && !bRefraction;
    bool alphaBlend = bAlphaBlend && !bRefraction;

    mediump vec2 screenCoord = gl_FragCoord.xy * RcpWindowSize;

    // Scaled by the largest component before squaring, as in water.fsh (fp16 overflow).
    HIGHP_OR_MEDIUMP float eyeScale = max(max(abs(EyeVector.x), abs(EyeVector.y)),
                                          max(abs(EyeVector.z), cMinEyeDistance));
    HIGHP_OR_MEDIUMP vec3 eyeScaled = EyeVector / eyeScale;
    HIGHP_OR_MEDIUMP float eyeScaledLength2 = dot(eyeScaled, eyeScaled);
    HIGHP_OR_MEDIUMP float eyeDistance = cMinEyeDistance;
    if (scaleDistortion || bFog) {
        eyeDistance = max(eyeScale * sqrt(eyeScaledLength2), cMinEyeDistance);
    }

    mediump vec3 bumpNormal = vec3(0.0, 1.0, 0.0);
    if (bDistortion) {
        // z-major map: the mean of both layers' normals as the demo forms it, then swizzled to
        // world (x, z, y).
        mediump vec3 bump = texture2D(NormalTex, BumpCoord0).rgb
                          + texture2D(NormalTex, BumpCoord1).rgb - 1.0;
        bumpNormal = bump.xzy;

        mediump float distortion = WaveDistortion;
        if (scaleDistortion) {
            distortion = min(WaveDistortion / eyeDistance, cMaxDistortion);  // as water.fsh
        }
        screenCoord -= bumpNormal.xz * distortion;  // texture units, as in water.fsh
    }

    mediump vec3 colour = texture2D(ReflectionTex, screenCoord).rgb;

    if (bRefraction) {
        mediump vec3 refraction = texture2D(RefractionTex, screenCoord).rgb;
        mediump float reflectance = cReflectionShare;
        if (fresnel) {
            HIGHP_OR_MEDIUMP vec3 eyeDirection;
            if (bNormaliseCubemap) {
                eyeDirection = textureCube(NormalisationCubeMap, EyeVector).rgb * 2.0 - 1.0;
            } else {
                eyeDirection = eyeScaled * inversesqrt(max(eyeScaledLength2, 1e-4));
            }
            // The accumulated normal as it is for Schlick (water.fsh), unit for the exact
            // reference.
            mediump vec3 normal = bumpNormal;
            if (bDistortion && bFresnelExact) {
                normal = bumpNormal * inversesqrt(max(dot(bumpNormal, bumpNormal), 1e-4));
            }
            mediump float cosIncidence = clamp(dot(normal, eyeDirection), 0.0, 1.0);
            if (bFresnelExact) {
                reflectance = fresnelExact(cosIncidence);
            } else {
                reflectance = fresnelSchlick(cosIncidence);
            }
        }
        colour = mix(refraction, colour, reflectance);
    }

    if (waterColour) {
        colour = mix(colour, WaterColour.rgb, WaterColour.a);
    }

    if (bFog) {
        colour = mix(colour, FogColour, clamp(eyeDistance * RcpMaxFogDepth, 0.0, 1.0));
    }

    mediump float alpha = 1.0;
    if (alphaBlend) {
        alpha = cBlendAlpha;
    }
    gl_FragColor = vec4(colour, alpha);
}
