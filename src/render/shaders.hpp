#pragma once
// GLSL sources. "#version 330 core" runs on the GLFW 3.3 context and on EGL's 4.5 context.

namespace pba::render::glsl {

// Particles as point sprites shaded like spheres: on the CPU rasteriser a point costs
// about half an instanced quad, which is what lets 100,000 particles stay interactive.
inline constexpr const char* kSpriteVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in float aRadius;
layout(location = 2) in vec4 aColour;
uniform mat4 uView;
uniform mat4 uProjection;
uniform float uViewportHeight;
out vec4 vColour;
void main() {
    vec4 eye = uView * vec4(aPosition, 1.0);
    gl_Position = uProjection * eye;
    // Diameter in pixels of a sphere of radius aRadius at this depth.
    gl_PointSize = max(2.0, 2.0 * aRadius * uProjection[1][1] * 0.5 * uViewportHeight / max(-eye.z, 1e-4));
    vColour = aColour;
}
)";

inline constexpr const char* kSpriteFragment = R"(#version 330 core
in vec4 vColour;
out vec4 fragColour;
void main() {
    vec2 p = gl_PointCoord * 2.0 - 1.0;
    float r2 = dot(p, p);
    if (r2 > 1.0) discard;
    vec3 normal = vec3(p.x, -p.y, sqrt(1.0 - r2));
    vec3 light = normalize(vec3(-0.4, 0.7, 0.6));
    float diffuse = max(dot(normal, light), 0.0);
    float specular = pow(max(dot(reflect(-light, normal), vec3(0, 0, 1)), 0.0), 24.0);
    fragColour = vec4(vColour.rgb * (0.35 + 0.65 * diffuse) + vec3(0.35 * specular), vColour.a);
}
)";

inline constexpr const char* kFlatVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aColour;
uniform mat4 uView;
uniform mat4 uProjection;
out vec4 vColour;
void main() {
    gl_Position = uProjection * uView * vec4(aPosition, 1.0);
    vColour = aColour;
}
)";

inline constexpr const char* kFlatFragment = R"(#version 330 core
in vec4 vColour;
out vec4 fragColour;
void main() { fragColour = vColour; }
)";

// A lit surface (a cloth, a rigid body's faces): lit from its normal on both sides (the back
// face's normal turned toward the eye), so a sheet folding over shows its shape from either side.
// A rigid body's faces are also shaded lighter or darker by the direction the point faces in the
// body's own frame (+x, -x, +y, -y, +z, -z), so a cube turned a quarter no longer looks as before
// and a ball's turning shows; chosen per pixel, a ball's patches meet on smooth curves. A die also
// has pips: 1 on +x opposite 6, 2 on +y opposite 5, 3 on +z opposite 4.
inline constexpr const char* kLitVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aColour;
layout(location = 3) in vec3 aBodyNormal;
layout(location = 4) in vec3 aOnDie;
layout(location = 5) in float aDie;
uniform mat4 uView;
uniform mat4 uProjection;
out vec3 vNormal;
out vec4 vColour;
out vec3 vBodyNormal;
out vec3 vOnDie;
out float vDie;
void main() {
    gl_Position = uProjection * uView * vec4(aPosition, 1.0);
    vNormal = mat3(uView) * aNormal;
    vColour = aColour;
    vBodyNormal = aBodyNormal;
    vOnDie = aOnDie;
    vDie = aDie;
}
)";

inline constexpr const char* kLitFragment = R"(#version 330 core
in vec3 vNormal;
in vec4 vColour;
in vec3 vBodyNormal;
in vec3 vOnDie;
in float vDie;
out vec4 fragColour;
const float kTowardsWhite[6] = float[6](0.0, 0.0, 0.55, 0.0, 0.28, 0.0);
const float kTowardsBlack[6] = float[6](0.0, 0.5, 0.0, 0.72, 0.0, 0.28);
const int kPips[6] = int[6](1, 6, 2, 5, 3, 4);
// How far (in half sides) the face point uv is from the nearest pip of a face showing n.
float pipDistance(int n, vec2 uv) {
    float d = 10.0;
    if (n == 1 || n == 3 || n == 5) d = min(d, length(uv));
    if (n >= 2) d = min(d, min(length(uv - vec2(0.5, 0.5)), length(uv + vec2(0.5, 0.5))));
    if (n >= 4) d = min(d, min(length(uv - vec2(0.5, -0.5)), length(uv + vec2(0.5, -0.5))));
    if (n == 6) d = min(d, min(length(uv - vec2(0.5, 0.0)), length(uv + vec2(0.5, 0.0))));
    return d;
}
void main() {
    vec3 rgb = vColour.rgb;
    vec3 a = abs(vBodyNormal);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    int face = 2 * axis + (vBodyNormal[axis] < 0.0 ? 1 : 0);
    if (a.x + a.y + a.z > 0.0) { // a rigid body's: not a cloth's
        rgb = mix(rgb, vec3(1.0), kTowardsWhite[face]);
        rgb = mix(rgb, vec3(0.0), kTowardsBlack[face]);
    }
    vec3 normal = length(vNormal) > 0.0 ? normalize(vNormal) : vec3(0, 0, 1);
    if (!gl_FrontFacing) normal = -normal;
    vec3 light = normalize(vec3(-0.4, 0.7, 0.6));
    float shade = 0.3 + 0.7 * abs(dot(normal, light));
    float specular = pow(max(dot(reflect(-light, normal), vec3(0, 0, 1)), 0.0), 16.0);
    if (vDie > 0.5) {
        vec2 uv = axis == 0 ? vOnDie.yz : (axis == 1 ? vOnDie.zx : vOnDie.xy);
        float d = pipDistance(kPips[face], uv);
        float edge = max(fwidth(d), 1e-4);
        float pip = 1.0 - smoothstep(0.17 - edge, 0.17 + edge, d);
        // Dark pips on a face that looks light, light ones on a face that looks dark (lit, as seen:
        // a light face turned from the light is dark).
        vec3 ink = dot(rgb * shade, vec3(0.3, 0.59, 0.11)) > 0.3 ? vec3(0.06) : vec3(0.95);
        rgb = mix(rgb, ink, pip);
    }
    fragColour = vec4(rgb * shade + vec3(0.15 * specular), vColour.a);
}
)";

inline constexpr const char* kFloorVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uView;
uniform mat4 uProjection;
out vec3 vWorld;
void main() {
    vWorld = aPosition;
    gl_Position = uProjection * uView * vec4(aPosition, 1.0);
}
)";

inline constexpr const char* kFloorFragment = R"(#version 330 core
in vec3 vWorld;
uniform float uCell;
uniform vec3 uHole; // x, z, radius
out vec4 fragColour;
void main() {
    vec2 xz = vWorld.xz;
    float hole = length(xz - uHole.xy);
    if (hole < uHole.z) {
        // The dryer's grille seen through the hole: dark, with bars.
        float bars = step(0.5, fract(xz.x / (uHole.z * 0.25)));
        fragColour = vec4(vec3(0.08 + 0.08 * bars), 1.0);
        return;
    }
    vec2 cell = floor(xz / uCell);
    float checker = mod(cell.x + cell.y, 2.0);
    vec3 colour = mix(vec3(0.78, 0.80, 0.84), vec3(0.62, 0.65, 0.70), checker);
    fragColour = vec4(colour, 1.0);
}
)";

} // namespace pba::render::glsl
