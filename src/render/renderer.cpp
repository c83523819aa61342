#include "renderer.hpp"

#include <epoxy/gl.h>

#include <cstddef>
#include <vector>

#include "shaders.hpp"

namespace pba::render {

Renderer::Renderer()
    : m_sprite("sprite", glsl::kSpriteVertex, glsl::kSpriteFragment),
      m_flat("flat", glsl::kFlatVertex, glsl::kFlatFragment),
      m_floor("floor", glsl::kFloorVertex, glsl::kFloorFragment),
      m_lit("lit", glsl::kLitVertex, glsl::kLitFragment)
{
    glGenVertexArrays(1, &m_vao);
    glGenBuffers(1, &m_vbo);
}

Renderer::~Renderer()
{
    glDeleteBuffers(1, &m_vbo);
    glDeleteVertexArrays(1, &m_vao);
}

void Renderer::draw(const DrawList& list, const OrbitCamera& camera, int width, int height, const glm::vec3& background)
{
    glClearColor(background.r, background.g, background.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT); // the whole target: the viewport may be narrower
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    const glm::mat4 view = camera.view();
    const glm::mat4 projection = camera.projection(float(width) / float(std::max(height, 1)));
    for (const Shader* shader : {&m_sprite, &m_flat, &m_floor, &m_lit}) {
        shader->use();
        shader->set("uView", view);
        shader->set("uProjection", projection);
    }
    m_sprite.use();
    m_sprite.set("uViewportHeight", float(height));
    glBindVertexArray(m_vao);
    glBindBuffer(GL_ARRAY_BUFFER, m_vbo);
    if (list.floor)
        drawFloor(*list.floor);
    drawColoured(list.lines, GL_LINES);
    drawSurfaces(list.surfaces);
    drawSprites(list.sprites);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    drawColoured(list.triangles, GL_TRIANGLES);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    // The marks (contacts, joint frames, axes) describe what lies inside or under the bodies:
    // drawn over everything, as a physics engine's debug drawing is.
    glDisable(GL_DEPTH_TEST);
    drawColoured(list.overlayLines, GL_LINES);
    drawSprites(list.overlaySprites);
    glEnable(GL_DEPTH_TEST);
    glBindVertexArray(0);
}

void Renderer::drawFloor(const Floor& floor)
{
    const glm::vec3 quad[6] = {{floor.min.x, floor.height, floor.min.y}, {floor.max.x, floor.height, floor.min.y},
                               {floor.max.x, floor.height, floor.max.y}, {floor.min.x, floor.height, floor.min.y},
                               {floor.max.x, floor.height, floor.max.y}, {floor.min.x, floor.height, floor.max.y}};
    m_floor.use();
    m_floor.set("uCell", floor.cell);
    m_floor.set("uHole", glm::vec3(floor.holeCentre, floor.holeRadius));
    glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glDisableVertexAttribArray(1);
    glDisableVertexAttribArray(2);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    // Pull the floor slightly back in depth so lines lying on it stay visible.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glDisable(GL_POLYGON_OFFSET_FILL);
}

namespace {

/// Sends a list of vertices to the bound buffer.
template <class Vertex>
void upload(const std::vector<Vertex>& vertices)
{
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(Vertex)), vertices.data(),
                 GL_STREAM_DRAW);
}

/// Points attribute `index` at `size` floats `offset` bytes into each Vertex.
template <class Vertex>
void attribute(GLuint index, GLint size, std::size_t offset)
{
    glEnableVertexAttribArray(index);
    glVertexAttribPointer(index, size, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(offset));
}

} // namespace

void Renderer::drawColoured(const std::vector<ColouredVertex>& vertices, unsigned mode)
{
    if (vertices.empty())
        return;
    m_flat.use();
    upload(vertices);
    attribute<ColouredVertex>(0, 3, offsetof(ColouredVertex, position));
    attribute<ColouredVertex>(1, 4, offsetof(ColouredVertex, colour));
    glDisableVertexAttribArray(2);
    glDrawArrays(mode, 0, static_cast<GLsizei>(vertices.size()));
}

void Renderer::drawSurfaces(const std::vector<LitVertex>& vertices)
{
    if (vertices.empty())
        return;
    m_lit.use();
    upload(vertices);
    attribute<LitVertex>(0, 3, offsetof(LitVertex, position));
    attribute<LitVertex>(1, 3, offsetof(LitVertex, normal));
    attribute<LitVertex>(2, 4, offsetof(LitVertex, colour));
    attribute<LitVertex>(3, 3, offsetof(LitVertex, bodyNormal));
    attribute<LitVertex>(4, 3, offsetof(LitVertex, onDie));
    attribute<LitVertex>(5, 1, offsetof(LitVertex, die));
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices.size()));
    for (GLuint index = 3; index < 6; ++index) // the other lists use the first three
        glDisableVertexAttribArray(index);
}

void Renderer::drawSprites(const std::vector<Sprite>& sprites)
{
    if (sprites.empty())
        return;
    m_sprite.use();
    glEnable(GL_PROGRAM_POINT_SIZE);
    glEnable(GL_BLEND); // ghosts are translucent
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    upload(sprites);
    attribute<Sprite>(0, 3, offsetof(Sprite, position));
    attribute<Sprite>(1, 1, offsetof(Sprite, radius));
    attribute<Sprite>(2, 4, offsetof(Sprite, colour));
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(sprites.size()));
    glDisable(GL_BLEND);
}

} // namespace pba::render
