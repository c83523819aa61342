#include "rigid/wide_contact_rows.hpp"

#include <algorithm>
#include <bit>

namespace pba::rigid {

namespace {

Vec4x3 load(const float (&a)[3][4]) { return {Float4::load(a[0]), Float4::load(a[1]), Float4::load(a[2])}; }

/// Lane k of a row of four from one point's row.
void put(float (&into)[3][4], int k, const glm::vec3& v)
{
    into[0][k] = v.x;
    into[1][k] = v.y;
    into[2][k] = v.z;
}

} // namespace

void WideContactRows::build(std::span<const IslandContact> contacts, std::span<const VelocityRows> rows,
                            std::span<const SolverBody> bodies, std::vector<std::uint32_t>& leftOver)
{
    m_blocks.clear();
    m_slots.clear();
    const std::vector<std::uint32_t>& start = m_colourContacts;
    leftOver.assign(m_byColour.begin() + start[kColours], m_byColour.end());
    for (int c = 0; c < kColours; ++c) {
        m_order.assign(m_byColour.begin() + start[c], m_byColour.begin() + start[c + 1]);
        // Like counts together: a block has as many slots as its lane with the most points.
        std::stable_sort(m_order.begin(), m_order.end(),
                         [&](std::uint32_t p, std::uint32_t q) { return contacts[p].count > contacts[q].count; });
        for (std::size_t first = 0; first < m_order.size(); first += 4)
            pack(contacts, rows, bodies, std::span(m_order).subspan(first, std::min<std::size_t>(4, m_order.size() - first)));
    }
}

void WideContactRows::colour(std::span<const IslandContact> contacts, std::span<const SolverBody> bodies)
{
    if (contacts.size() < kFewest) { // all of them one at a time, in order
        m_byColour.resize(contacts.size());
        for (std::uint32_t c = 0; c < contacts.size(); ++c)
            m_byColour[c] = c;
        std::fill(m_colourContacts.begin(), m_colourContacts.end() - 1, 0u);
        m_colourContacts.back() = std::uint32_t(contacts.size());
        return;
    }
    // Greedy, in the contacts' order: a static body (the floor, a fixed ramp) is never written,
    // so it may be in every contact of a colour.
    if (m_used.size() < bodies.size())
        m_used.resize(bodies.size(), 0);
    m_colour.assign(contacts.size(), kColours);
    for (std::size_t c = 0; c < contacts.size(); ++c) {
        const IslandContact& s = contacts[c];
        const bool movesA = !bodies[s.a].isStatic(), movesB = !bodies[s.b].isStatic();
        const std::uint32_t taken = (movesA ? m_used[s.a] : 0u) | (movesB ? m_used[s.b] : 0u);
        const int colour = std::countr_one(taken);
        if (colour >= kColours)
            continue;
        m_colour[c] = std::uint8_t(colour);
        if (movesA)
            m_used[s.a] |= 1u << colour;
        if (movesB)
            m_used[s.b] |= 1u << colour;
    }
    for (const IslandContact& s : contacts)
        m_used[s.a] = m_used[s.b] = 0;
    // The contacts by colour, each colour's in order (a counting sort); those no colour took last.
    std::vector<std::uint32_t>& start = m_colourContacts;
    std::fill(start.begin(), start.end(), 0u);
    for (const std::uint8_t c : m_colour)
        ++start[c + 1];
    for (int c = 0; c <= kColours; ++c)
        start[c + 1] += start[c];
    m_byColour.resize(contacts.size());
    std::uint32_t fill[kColours + 1];
    std::copy(start.begin(), start.begin() + kColours + 1, fill);
    for (std::uint32_t c = 0; c < contacts.size(); ++c)
        m_byColour[fill[m_colour[c]]++] = c;
}

void WideContactRows::pack(std::span<const IslandContact> contacts, std::span<const VelocityRows> rows,
                           std::span<const SolverBody> bodies, std::span<const std::uint32_t> lanes)
{
    Block block;
    block.firstSlot = std::uint32_t(m_slots.size());
    for (const std::uint32_t c : lanes)
        block.slots = std::max(block.slots, std::uint32_t(contacts[c].count));
    m_slots.resize(m_slots.size() + block.slots);
    alignas(16) float friction[4] = {}, inverseMass[2][4] = {};
    for (std::size_t k = 0; k < 4; ++k) {
        const bool real = k < lanes.size();
        const IslandContact& s = contacts[lanes[real ? k : 0]]; // an empty lane reads its first lane's bodies
        block.contact[k] = real ? lanes[k] : kEmptyLane;
        block.body[0][k] = s.a;
        block.body[1][k] = s.b;
        block.moves[0][k] = real && !bodies[s.a].isStatic();
        block.moves[1][k] = real && !bodies[s.b].isStatic();
        friction[k] = real ? float(s.friction) : 0.0f;
        inverseMass[0][k] = real ? float(bodies[s.a].inverseMass) : 0.0f;
        inverseMass[1][k] = real ? float(bodies[s.b].inverseMass) : 0.0f;
    }
    block.friction = Float4::load(friction);
    block.inverseMass[0] = Float4::load(inverseMass[0]);
    block.inverseMass[1] = Float4::load(inverseMass[1]);
    // An empty lane (or a point a lane's contact lacks) has no mass and no impulse: its rows
    // change nothing.
    static const VelocityRows kNone{};
    for (std::uint32_t i = 0; i < block.slots; ++i) {
        Slot& slot = m_slots[block.firstSlot + i];
        for (std::size_t k = 0; k < 4; ++k) {
            const bool real = k < lanes.size() && int(i) < contacts[lanes[k]].count;
            const std::uint32_t r = real ? contacts[lanes[k]].first + i : kEmptyLane;
            slot.source[k] = r;
            const VelocityRows& v = real ? rows[r] : kNone;
            const Jacobian* j[3] = {&v.along, &v.across[0], &v.across[1]};
            const double impulse[3] = {v.normalImpulse, v.tangentImpulse[0], v.tangentImpulse[1]};
            for (int row = 0; row < 3; ++row) {
                WideRow& w = slot.row[row];
                put(w.u, int(k), j[row]->u);
                put(w.momentA, int(k), j[row]->momentA);
                put(w.momentB, int(k), j[row]->momentB);
                put(w.turnA, int(k), j[row]->turnA);
                put(w.turnB, int(k), j[row]->turnB);
                w.mass[k] = j[row]->mass;
                w.impulse[k] = float(impulse[row]);
            }
            slot.target[k] = float(v.target);
        }
    }
    m_blocks.push_back(block);
}

void WideContactRows::solveFriction(Slot& slot, const Block& block, Vec4x3 (&v)[2], Vec4x3 (&w)[2], Float4& change)
{
    Float4 want[2];
    for (int k = 0; k < 2; ++k) {
        const WideRow& r = slot.row[1 + k];
        const Float4 speed = dot(load(r.u), v[1] - v[0]) + dot(load(r.momentB), w[1]) - dot(load(r.momentA), w[0]);
        want[k] = Float4::load(r.impulse) - Float4::load(r.mass) * speed;
    }
    const Float4 square = want[0] * want[0] + want[1] * want[1];
    const Float4 limit = block.friction * Float4::load(slot.row[0].impulse);
    // Outside the cone, back onto it (where the square is 0 the quotient is not taken).
    const Float4 scale = selectGreater(square, limit * limit, limit / sqrt(square), Float4::all(1.0f));
    for (int k = 0; k < 2; ++k) {
        WideRow& r = slot.row[1 + k];
        const Float4 next = want[k] * scale;
        const Float4 d = next - Float4::load(r.impulse);
        const Vec4x3 u = load(r.u);
        v[0] = v[0] - (d * block.inverseMass[0]) * u;
        w[0] = w[0] - d * load(r.turnA);
        v[1] = v[1] + (d * block.inverseMass[1]) * u;
        w[1] = w[1] + d * load(r.turnB);
        change = max(change, abs(d));
        next.store(r.impulse);
    }
}

void WideContactRows::solveNormal(Slot& slot, const Block& block, Vec4x3 (&v)[2], Vec4x3 (&w)[2], Float4& change,
                                  Float4& largest)
{
    WideRow& r = slot.row[0];
    const Vec4x3 u = load(r.u);
    const Float4 speed = dot(u, v[1] - v[0]) + dot(load(r.momentB), w[1]) - dot(load(r.momentA), w[0]);
    const Float4 impulse = Float4::load(r.impulse);
    const Float4 next = max(impulse - Float4::load(r.mass) * (speed - Float4::load(slot.target)), Float4::zero());
    const Float4 d = next - impulse;
    v[0] = v[0] - (d * block.inverseMass[0]) * u;
    w[0] = w[0] - d * load(r.turnA);
    v[1] = v[1] + (d * block.inverseMass[1]) * u;
    w[1] = w[1] + d * load(r.turnB);
    change = max(change, abs(d));
    largest = max(largest, next);
    next.store(r.impulse);
}

void WideContactRows::sweepBlock(const Block& block, std::span<SolverBody> bodies, Float4& changed, Float4& most)
{
    // The four lanes' bodies, read into floats; only the changes go back, in double.
    alignas(16) float in[2][6][4];
    for (int side = 0; side < 2; ++side)
        for (int k = 0; k < 4; ++k) {
            const SolverBody& b = bodies[block.body[side][k]];
            for (int c = 0; c < 3; ++c) {
                in[side][c][k] = float(b.v[c]);
                in[side][3 + c][k] = float(b.w[c]);
            }
        }
    Vec4x3 v[2], w[2];
    for (int side = 0; side < 2; ++side) {
        v[side] = {Float4::load(in[side][0]), Float4::load(in[side][1]), Float4::load(in[side][2])};
        w[side] = {Float4::load(in[side][3]), Float4::load(in[side][4]), Float4::load(in[side][5])};
    }
    // As one contact at a time: its points' friction, then their normals.
    for (std::uint32_t i = 0; i < block.slots; ++i)
        solveFriction(m_slots[block.firstSlot + i], block, v, w, changed);
    for (std::uint32_t i = 0; i < block.slots; ++i)
        solveNormal(m_slots[block.firstSlot + i], block, v, w, changed, most);
    alignas(16) float out[2][6][4];
    for (int side = 0; side < 2; ++side) {
        v[side].x.store(out[side][0]);
        v[side].y.store(out[side][1]);
        v[side].z.store(out[side][2]);
        w[side].x.store(out[side][3]);
        w[side].y.store(out[side][4]);
        w[side].z.store(out[side][5]);
    }
    for (int side = 0; side < 2; ++side)
        for (int k = 0; k < 4; ++k) {
            if (!block.moves[side][k])
                continue;
            SolverBody& b = bodies[block.body[side][k]];
            for (int c = 0; c < 3; ++c) {
                b.v[c] += double(out[side][c][k] - in[side][c][k]);
                b.w[c] += double(out[side][3 + c][k] - in[side][3 + c][k]);
            }
        }
}

void WideContactRows::sweep(std::span<SolverBody> bodies, double& change, double& largest)
{
    Float4 changed = Float4::zero(), most = Float4::zero();
    for (const Block& block : m_blocks)
        sweepBlock(block, bodies, changed, most);
    alignas(16) float c[4], l[4];
    changed.store(c);
    most.store(l);
    for (int k = 0; k < 4; ++k) {
        change = std::max(change, double(c[k]));
        largest = std::max(largest, double(l[k]));
    }
}

std::vector<std::uint32_t> WideContactRows::order() const
{
    std::vector<std::uint32_t> out;
    for (const Block& block : m_blocks)
        out.insert(out.end(), block.contact, block.contact + 4);
    return out;
}

void WideContactRows::storeImpulses(std::span<VelocityRows> rows) const
{
    for (const Slot& slot : m_slots) {
        for (int k = 0; k < 4; ++k) {
            if (slot.source[k] == kEmptyLane)
                continue;
            VelocityRows& r = rows[slot.source[k]];
            r.normalImpulse = slot.row[0].impulse[k];
            r.tangentImpulse[0] = slot.row[1].impulse[k];
            r.tangentImpulse[1] = slot.row[2].impulse[k];
        }
    }
}

void WideContactRows::loadImpulses(std::span<const VelocityRows> rows)
{
    for (Slot& slot : m_slots) {
        for (int k = 0; k < 4; ++k) {
            if (slot.source[k] == kEmptyLane)
                continue;
            const VelocityRows& r = rows[slot.source[k]];
            slot.row[0].impulse[k] = float(r.normalImpulse);
            slot.row[1].impulse[k] = float(r.tangentImpulse[0]);
            slot.row[2].impulse[k] = float(r.tangentImpulse[1]);
        }
    }
}

} // namespace pba::rigid
