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

// A cloth: lit from its per-vertex normal, two-sided (the back face's normal is turned toward
// the eye), so a sheet folding over shows its shape from either side.
inline constexpr const char* kLitVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec4 aColour;
uniform mat4 uView;
uniform mat4 uProjection;
out vec3 vNormal;
out vec4 vColour;
void main() {
    gl_Position = uProjection * uView * vec4(aPosition, 1.0);
    vNormal = mat3(uView) * aNormal;
    vColour = aColour;
}
)";

inline constexpr const char* kLitFragment = R"(#version 330 core
in vec3 vNormal;
in vec4 vColour;
out vec4 fragColour;
void main() {
    vec3 normal = length(vNormal) > 0.0 ? normalize(vNormal) : vec3(0, 0, 1);
    if (!gl_FrontFacing) normal = -normal;
    vec3 light = normalize(vec3(-0.4, 0.7, 0.6));
    float diffuse = abs(dot(normal, light));
    float specular = pow(max(dot(reflect(-light, normal), vec3(0, 0, 1)), 0.0), 16.0);
    fragColour = vec4(vColour.rgb * (0.3 + 0.7 * diffuse) + vec3(0.15 * specular), vColour.a);
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
