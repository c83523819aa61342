#pragma once
// Body: what every simulated object has (the practical's class diagram).
// Particle derives from it today; rigid bodies will add orientation, angular
// velocity and an inertia tensor in a subclass of their own.
#include <memory>
#include <span>
#include <string>

#include "pba/integrator.hpp"
#include "pba/math.hpp"
#include "pba/mesh.hpp"
#include "pba/state.hpp"

namespace pba {

/// A point of a body's surface, in its own frame, and its share of the whole surface's area:
/// where a force spread over the surface (the blow dryer's) acts on an extended body.
struct SurfaceSample {
    dvec3 point{0.0};
    double share = 0.0; ///< the shares of a body's samples add up to 1
};

/// A body's surface samples, and whether they turn with it (a sphere's need not: its surface is
/// the same in every orientation, and samples fixed in the world keep a ball on the jet's axis
/// free of torque to rounding).
struct Surface {
    std::span<const SurfaceSample> samples; ///< empty: a point (a particle)
    bool turnsWithBody = true;
};

class alignas(64) Body {
public:
    virtual ~Body() = default;
    /// Deep copy through the base class, so a World (and a scene's reset) can copy its bodies.
    virtual std::unique_ptr<Body> clone() const = 0;
    /// Where forces spread over a surface act: none for a point.
    virtual Surface surface() const { return {}; }

    // ---- get methods (the practical's names) ----
    Mesh& getMesh() { return m_mesh; }
    const Mesh& getMesh() const { return m_mesh; }
    /// The body's position as a translation: where its mesh is drawn (the mesh has no position).
    glm::mat4 getTranslate() const;
    /// Where the mesh's vertices are drawn: the body's translation times the mesh's own frame.
    glm::mat4 getModel() const { return getTranslate() * m_mesh.getLocal(); }

    dvec3& getAcc() { return m_acc; }
    dvec3& getVel() { return m_vel; }
    const dvec3& getAcc() const { return m_acc; }
    const dvec3& getVel() const { return m_vel; }
    const dvec3& getPos() const { return m_pos; }

    double getMass() const { return m_mass; }
    double getCor() const { return m_cor; }

    // ---- set methods ----
    void setMesh(Mesh mesh);
    void setAcc(const dvec3& acc) { m_acc = acc; }
    void setVel(const dvec3& vel) { m_vel = vel; }
    void setVel(int i, double v) { m_vel[i] = v; }
    void setPos(const dvec3& pos) { m_pos = pos; }
    void setPos(int i, double p) { m_pos[i] = p; }
    /// Throws std::invalid_argument unless mass is finite and positive.
    void setMass(double mass);
    /// Coefficient of restitution; throws std::invalid_argument outside [0, 1].
    void setCor(double cor);

    // ---- transformation: the body moves, its mesh is drawn where it is ----
    /// Moves the body by `offset`. A body's mesh is turned and scaled in its own frame through
    /// getMesh() (Mesh::rotate, Mesh::scale), which moves nothing.
    void translate(const dvec3& offset) { m_pos += offset; }

    // ---- pba's additions ----
    const std::string& getName() const { return m_name; }
    void setName(std::string name) { m_name = std::move(name); }
    Integrator getIntegrator() const { return m_integrator; }
    void setIntegrator(Integrator integrator) { m_integrator = integrator; }
    /// A fixed body receives no force and never moves (the integrator scene's reference).
    bool isFixed() const { return m_fixed; }
    void setFixed(bool fixed) { m_fixed = fixed; }

    State getState() const { return {m_pos, m_vel}; }
    void setState(const State& state)
    {
        setPos(state.pos);
        m_vel = state.vel;
    }

protected:
    Body() = default;
    Body(const Body&) = default;
    Body& operator=(const Body&) = default;

private:
    // What a step reads and writes comes first and fits the object's first two cache lines (the
    // class is aligned to them): a cloth's step visits every body's object twice, in memory far
    // from the others', and each line is felt.
    double m_mass = 1.0;  ///< mass, kg
    double m_cor = 1.0;   ///< coefficient of restitution in [0, 1]
    dvec3 m_acc{0.0};     ///< acceleration at the start of the last step (its first force evaluation), m/s^2
    dvec3 m_vel{0.0};     ///< velocity, m/s
    dvec3 m_pos{0.0};     ///< position, m
    Integrator m_integrator = Integrator::SemiImplicitEuler;
    bool m_fixed = false;
    Mesh m_mesh;          ///< the mesh drawn for the body, in the body's own frame
    std::string m_name;
};

} // namespace pba
