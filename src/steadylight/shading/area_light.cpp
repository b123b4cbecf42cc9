// Area lights: the surface of an emissive object, sampled uniformly by area (triangles chosen
// in proportion to their area; spheres over their whole surface) for photons. Seen from a point
// they light, a rectangle (two triangles) is sampled by the solid angle it covers
// (spherical_rectangle.h) unless that is too small to pay or too large for the
// parametrization's precision, and a sphere by the cone of directions that see it (every
// sample lands on its visible side, where area samples waste the hidden half and more).
#include <algorithm>
#include <cmath>

#include "steadylight/base/error.h"
#include "steadylight/base/sampling.h"
#include "steadylight/shading/light.h"
#include "steadylight/shading/spherical_rectangle.h"
#include "steadylight/shading/surface_point.h"

namespace steadylight {
namespace {

struct Triangle {
    Vec3 p0, p1, p2, n;
    int primitive = 0;  // index in the mesh, for the emissive texture
};

/// An emitter's emissive texture, read where a sample lands.
struct EmissiveTexture {
    const SceneDesc* desc = nullptr;
    const MaterialDesc* material = nullptr;
    const TriangleMesh* mesh = nullptr;

    bool is_set() const { return material && material->emissive_texture.is_set(); }
    Rgb tint(int primitive, Vec2 b) const {
        if (!is_set()) return {1, 1, 1};
        return emissive_tint_at(*desc, *material, surface_attributes(*mesh, {primitive, b.x, b.y}));
    }
};

class AreaLight final : public Light {
public:
    AreaLight(const ObjectDesc& object, Rgb Le, std::vector<Triangle> triangles, std::vector<float> cdf, float area,
              EmissiveTexture texture)
        : m_object(object),
          m_Le(Le),
          m_triangles(std::move(triangles)),
          m_cdf(std::move(cdf)),
          m_area(area),
          m_texture(texture) {
        bound_triangles();
        if (m_triangles.size() == 2 && dot(m_triangles[0].n, m_triangles[1].n) > 0.9999f)
            m_rectangle = rectangle_of({m_triangles[0].p0, m_triangles[0].p1, m_triangles[0].p2},
                                       {m_triangles[1].p0, m_triangles[1].p1, m_triangles[1].p2});
        // Lights are chosen by power: a textured one by its image's average (its uv layout is not weighed).
        m_mean_Le =
            m_texture.is_set()
                ? m_Le * average_color(m_texture.desc->images[size_t(m_texture.material->emissive_texture.image)], true)
                : m_Le;
    }

    AreaLight(const ObjectDesc& object, Rgb Le, Vec3 center, float radius)
        : m_object(object),
          m_Le(Le),
          m_mean_Le(Le),
          m_center(center),
          m_radius(radius),
          m_area(4 * pi * radius * radius),
          m_bound_radius(radius) {}

    std::optional<LightSample> sample_li(Vec3 ref, Vec2 u, Vec3) const override {
        LightSample s;
        Rgb tint;
        const std::optional<SphericalRectangle> seen = seen_by_solid_angle(ref);
        const std::optional<float> cone = cone_seen_from(ref);
        if (seen) {
            s.p = seen->sample(u);
            s.n = m_triangles[0].n;
            tint = tint_on_rectangle(s.p);
        } else if (cone) {
            s.p = sample_in_cone(ref, *cone, u);
            s.n = normalize(s.p - m_center);
            tint = {1, 1, 1};
        } else {
            tint = sample_point(u, s.p, s.n);
        }
        const Vec3 d = s.p - ref;
        s.distance = length(d);
        if (!(s.distance > 0)) return std::nullopt;
        s.wi = d / s.distance;
        s.Li = emitted_radiance(m_object, m_Le * tint, s.n, -s.wi);
        s.pdf = seen   ? 1 / seen->solid_angle()
                : cone ? uniform_cone_pdf(1 - *cone)
                       : area_to_solid_angle(1 / m_area, ref, s.p, s.n);
        if (is_black(s.Li) || !(s.pdf > 0)) return std::nullopt;
        return s;
    }

    float pdf_li(Vec3 ref, Vec3 p, Vec3 n) const override {
        if (const std::optional<SphericalRectangle> seen = seen_by_solid_angle(ref)) return 1 / seen->solid_angle();
        if (const std::optional<float> cone = cone_seen_from(ref)) return uniform_cone_pdf(1 - *cone);
        return area_to_solid_angle(1 / m_area, ref, p, n);
    }

    float power() const override { return luminance(m_mean_Le) * pi * m_area * sides(); }

    float importance(Vec3 ref, Vec3 n) const override {
        // The area a sphere shows from any side is a quarter of its surface.
        const float shown_area = m_triangles.empty() ? m_area / 4 : m_area;
        return importance_bound(luminance(m_mean_Le) * shown_area, ref, n, m_center, m_bound_radius, m_bound_normal);
    }

    std::optional<EmissionSample> sample_emission(Vec2 u_position, Vec2 u_direction) const override {
        EmissionSample s;
        const Rgb tint = sample_point(u_position, s.p, s.n);
        // A two-sided emitter picks its side with the first direction number, then reuses it.
        if (m_object.two_sided_emission) {
            const bool back = u_direction.x < 0.5f;
            u_direction.x = back ? 2 * u_direction.x : 2 * u_direction.x - 1;
            if (back) s.n = -s.n;
        }
        // Cosine-weighted directions: Le cos / (pdf_area pdf_direction) = Le pi A (per side).
        s.d = OrthonormalBasis::from_normal(s.n).to_world(sample_cosine_hemisphere(u_direction));
        s.power = m_Le * tint * (pi * m_area * sides());
        return s;
    }

    EmissionPoint sample_emission_point(Vec2 u) const override {
        EmissionPoint at;
        sample_point(u, at.p, at.n);
        at.pdf = 1 / m_area;
        return at;
    }

    Rgb emitted_intensity(const EmissionPoint& at, Vec3 d) const override {
        return emitted_radiance(m_object, m_Le, at.n, d) * std::abs(dot(at.n, d));
    }

    BoundingSphere bounds() const override { return {m_center, m_bound_radius}; }

private:
    /// Bounds the triangles by a sphere about their area-weighted centre, and keeps their
    /// normal if they are one flat, one-sided emitter.
    void bound_triangles() {
        m_center = {};
        for (size_t i = 0; i < m_triangles.size(); ++i) {
            const Triangle& t = m_triangles[i];
            const float share = m_cdf[i] - (i ? m_cdf[i - 1] : 0);
            m_center += (t.p0 + t.p1 + t.p2) * (share / 3);
        }
        bool flat = !m_object.two_sided_emission;
        for (const Triangle& t : m_triangles) {
            for (const Vec3 p : {t.p0, t.p1, t.p2}) m_bound_radius = std::max(m_bound_radius, length(p - m_center));
            flat = flat && dot(t.n, m_triangles[0].n) > 0.9999f;
        }
        m_bound_radius *= 1.0001f;  // rounding
        if (flat) m_bound_normal = m_triangles[0].n;
    }

    float sides() const { return m_object.two_sided_emission ? 2.0f : 1.0f; }

    /// The rectangle as seen from `ref`, when it is one and its solid angle is within what the
    /// parametrization samples precisely (a near-hemisphere one has a singular edge) and large
    /// enough to pay: a light seen under less than 0.01 sr (a 0.3 m panel from 3 m) is lit
    /// about evenly by area samples too, which cost less. The last answer is kept per thread,
    /// keyed by the rectangle and the point (not by this light, whose address a later frame's
    /// light may take): a shading point asks once per light sample, every time from the same point.
    std::optional<SphericalRectangle> seen_by_solid_angle(Vec3 ref) const {
        if (!m_rectangle) return std::nullopt;
        thread_local Rectangle last_rectangle{};
        thread_local Vec3 last_ref;
        thread_local std::optional<SphericalRectangle> last_seen;
        const Rectangle& r = *m_rectangle;
        const bool same = last_ref == ref && last_rectangle.corner == r.corner && last_rectangle.edge_u == r.edge_u &&
                          last_rectangle.edge_v == r.edge_v;
        if (!same) {  // (at first the edges are zero, which a rectangle's never are)
            const SphericalRectangle seen(r, ref);
            last_rectangle = r, last_ref = ref;
            last_seen = seen.solid_angle() > 0.01f && seen.solid_angle() < 6.22f ? std::optional(seen) : std::nullopt;
        }
        return last_seen;
    }

    /// For a sphere seen from outside it, 1 - cos of the half-angle of the cone of directions
    /// from `ref` that meet it (as sin^2 / (1 + cos): no cancellation for a small, far sphere).
    std::optional<float> cone_seen_from(Vec3 ref) const {
        if (!m_triangles.empty()) return std::nullopt;
        const float distance2 = length2(m_center - ref), radius2 = m_radius * m_radius;
        if (!(distance2 > radius2 * 1.0001f)) return std::nullopt;  // inside or on it: by area
        const float sin2 = radius2 / distance2;
        return sin2 / (1 + std::sqrt(1 - sin2));
    }

    /// The point of the sphere's near side in a direction uniform within that cone.
    Vec3 sample_in_cone(Vec3 ref, float one_minus_cos_max, Vec2 u) const {
        const Vec3 to_center = m_center - ref;
        const float distance = length(to_center);
        const float one_minus_cos = u.x * one_minus_cos_max;
        const float cos_theta = 1 - one_minus_cos, sin2_theta = one_minus_cos * (2 - one_minus_cos);
        const float sin_theta = std::sqrt(std::max(0.0f, sin2_theta)), phi = 2 * pi * u.y;
        const Vec3 wi = OrthonormalBasis::from_normal(to_center / distance)
                            .to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta});
        // The nearer hit of ref + t wi: t = d cos - sqrt(R^2 - d^2 sin^2).
        const float t =
            distance * cos_theta - std::sqrt(std::max(0.0f, m_radius * m_radius - distance * distance * sin2_theta));
        return ref + wi * t;
    }

    /// The emissive texture's tint at a point of the rectangle (its triangle's barycentrics).
    Rgb tint_on_rectangle(Vec3 p) const {
        if (!m_texture.is_set()) return {1, 1, 1};
        for (const Triangle& t : m_triangles) {
            const Vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0, q = p - t.p0;
            const float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), q1 = dot(q, e1), q2 = dot(q, e2);
            const float det = d11 * d22 - d12 * d12;
            const Vec2 b{(d22 * q1 - d12 * q2) / det, (d11 * q2 - d12 * q1) / det};
            if ((b.x >= -1e-4f && b.y >= -1e-4f && b.x + b.y <= 1 + 1e-4f) || &t == &m_triangles.back())
                return m_texture.tint(t.primitive, {std::clamp(b.x, 0.0f, 1.0f), std::clamp(b.y, 0.0f, 1.0f)});
        }
        return {1, 1, 1};
    }

    /// A point uniform by area, and the emissive texture's tint there.
    Rgb sample_point(Vec2 u, Vec3& p, Vec3& n) const {
        if (m_triangles.empty()) {
            n = sample_uniform_sphere(u);
            p = m_center + n * m_radius;
            return {1, 1, 1};
        }
        // Choose a triangle with u.x, then reuse the remainder of u.x inside it.
        const size_t i =
            std::min(size_t(std::upper_bound(m_cdf.begin(), m_cdf.end(), u.x) - m_cdf.begin()), m_triangles.size() - 1);
        const float lo = i ? m_cdf[i - 1] : 0;
        const float ux = std::clamp((u.x - lo) / std::max(m_cdf[i] - lo, 1e-20f), 0.0f, 0x1.fffffep-1f);
        const Vec2 b = sample_uniform_triangle({ux, u.y});
        const Triangle& t = m_triangles[i];
        p = t.p0 * (1 - b.x - b.y) + t.p1 * b.x + t.p2 * b.y;
        n = t.n;
        return m_texture.tint(t.primitive, b);
    }

    const ObjectDesc& m_object;
    Rgb m_Le;       // emitted radiance at this frame, before the emissive texture
    Rgb m_mean_Le;  // times the texture's average colour
    std::vector<Triangle> m_triangles;
    std::vector<float> m_cdf;
    Vec3 m_center;
    float m_radius = 0;
    float m_area = 0;
    float m_bound_radius = 0;              // about m_center
    Vec3 m_bound_normal;                   // zero unless flat and one-sided
    std::optional<Rectangle> m_rectangle;  // when the emitter is one (two triangles)
    EmissiveTexture m_texture;
};

std::unique_ptr<Light> make_mesh_light(const ObjectDesc& object, Rgb Le, const TriangleMesh& mesh,
                                       const Transform& world_from_object, EmissiveTexture texture) {
    std::vector<Triangle> triangles;
    std::vector<float> cdf;
    float area = 0;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        Triangle t{world_from_object.point(mesh.positions[size_t(mesh.indices[i])]),
                   world_from_object.point(mesh.positions[size_t(mesh.indices[i + 1])]),
                   world_from_object.point(mesh.positions[size_t(mesh.indices[i + 2])]),
                   {},
                   int(i / 3)};
        const Vec3 c = cross(t.p1 - t.p0, t.p2 - t.p0);
        const float a = 0.5f * length(c);
        if (!(a > 0)) continue;
        t.n = c / (2 * a);
        // Vertex normals decide the front side, as for ray hits (surface_point.cpp).
        if (!mesh.normals.empty()) {
            const Vec3 ns = world_from_object.normal(mesh.normals[size_t(mesh.indices[i])]);
            if (dot(ns, t.n) < 0) t.n = -t.n;
        }
        area += a;
        triangles.push_back(t);
        cdf.push_back(area);
    }
    if (!(area > 0)) throw InputError(object.name, "emitter has zero area");
    for (float& c : cdf) c /= area;
    cdf.back() = 1;
    return std::make_unique<AreaLight>(object, Le, std::move(triangles), std::move(cdf), area, texture);
}

}  // namespace

std::unique_ptr<Light> make_area_light(const Scene& scene, const FrameState& frame, int object) {
    const ObjectDesc& desc = scene.object(object);
    const Transform& world_from_object = frame.world_from_object[size_t(object)];
    const Rgb Le = frame.emission[size_t(object)];
    if (const auto* mesh = std::get_if<TriangleMesh>(&desc.geometry))
        return make_mesh_light(desc, Le, *mesh, world_from_object,
                               {&scene.desc(), &scene.desc().materials[size_t(desc.material)], mesh});
    // A sphere light must stay a sphere: uneven scaling would need ellipsoid sampling.
    const Sphere& sphere = std::get<Sphere>(desc.geometry);
    const float sx = length(world_from_object.vector({1, 0, 0}));
    const float sy = length(world_from_object.vector({0, 1, 0}));
    const float sz = length(world_from_object.vector({0, 0, 1}));
    if (std::abs(sx - sy) > 1e-4f * sx || std::abs(sx - sz) > 1e-4f * sx)
        throw InputError(desc.name, "an emissive sphere must be scaled uniformly");
    return std::make_unique<AreaLight>(desc, Le, world_from_object.point(sphere.center), sphere.radius * sx);
}

}  // namespace steadylight
