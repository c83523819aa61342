#pragma once
// Turns a DrawList into OpenGL calls. Needs a current OpenGL 3.3 core context.
#include <memory>

#include "camera.hpp"
#include "draw_list.hpp"
#include "shader.hpp"

namespace pba::render {

class Renderer {
public:
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Clears the target to `background` and draws into its bottom-left width x height (the
    /// viewer's room beside its panel, or the whole image): floor, lines and sprites with depth, then the
    /// translucent triangles blended on top without writing depth, and last the overlay's marks
    /// with no depth test.
    void draw(const DrawList& list, const OrbitCamera& camera, int width, int height,
              const glm::vec3& background = glm::vec3(0.11f, 0.12f, 0.15f));

private:
    void drawFloor(const Floor& floor);
    void drawColoured(const std::vector<ColouredVertex>& vertices, unsigned mode);
    void drawSprites(const std::vector<Sprite>& sprites);
    void drawSurfaces(const std::vector<LitVertex>& vertices);

    Shader m_sprite;
    Shader m_flat;
    Shader m_floor;
    Shader m_lit;
    unsigned m_vao = 0;
    unsigned m_vbo = 0;
};

} // namespace pba::render
