// Scene: the prepared, immutable scene. It owns the SceneDesc, splits objects into static and
// dynamic and the animation into segments (docs/design.md), and answers `evaluate(frame)`: where
// the camera and every object are at that frame, and how bright every light is. It knows
// nothing of Embree; trace/ builds acceleration structures from it.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "steadylight/base/bounding_sphere.h"
#include "steadylight/base/ray.h"
#include "steadylight/scene/distant_photon_targets.h"
#include "steadylight/scene/scene_desc.h"

namespace steadylight {

/// A pinhole camera at one frame. Pixel (0,0) is the top-left; image right is camera +x.
struct Camera {
    Transform world_from_camera;
    float tan_half_fov_y = 0;
    int width = 0;
    int height = 0;
    /// Camera rays that leave the scene see nothing of the world: those pixels are transparent
    /// (CameraDesc::transparent_background). The world seen through glass or in a mirror stays.
    bool transparent_background = false;

    /// The primary ray through film position (x, y) in pixels, e.g. (10.5, 3.5) is a centre.
    Ray generate_ray(float x, float y) const;
    /// The film position (in pixels) where world point `p` appears, if it is in front of the camera.
    std::optional<Vec2> project(Vec3 p) const;
    /// The world-space width of one pixel at distance `distance` from the camera.
    float pixel_footprint(float distance) const { return distance * 2 * tan_half_fov_y / float(height); }
};

/// Frames [first, last] whose lighting is coherent: they share one static irradiance cache.
struct Segment {
    int first = 0;
    int last = 0;
};

/// Where everything is at one frame, and how brightly it shines.
struct FrameState {
    int frame = 0;
    float time_s = 0;
    Camera camera;
    std::vector<Transform> world_from_object;  // one per object
    std::vector<Rgb> emission;                 // one per object: its emitted radiance (black: off, or no light)
    std::vector<PointLightPose> point_lights;  // one per point or spot light (black intensity: off)
    std::vector<Vec3> sun_directions;          // one per sun: the way its light travels

    /// True when every light, lamps and suns, is where and as bright as in `other` (the same scene).
    bool same_lights(const FrameState& other) const {
        return same_light_levels(other) && point_lights == other.point_lights && sun_directions == other.sun_directions;
    }
    /// True when every light is as bright as in `other`, wherever it stands.
    bool same_light_levels(const FrameState& other) const {
        if (emission != other.emission || point_lights.size() != other.point_lights.size()) return false;
        for (size_t i = 0; i < point_lights.size(); ++i)
            if (point_lights[i].intensity != other.point_lights[i].intensity) return false;
        return true;
    }
};

class Scene {
public:
    explicit Scene(SceneDesc desc);

    const SceneDesc& desc() const { return m_desc; }
    const std::string& name() const { return m_desc.name; }
    const std::vector<ObjectDesc>& objects() const { return m_desc.objects; }
    const ObjectDesc& object(int index) const { return m_desc.objects[size_t(index)]; }
    const std::vector<int>& static_objects() const { return m_static; }
    const std::vector<int>& dynamic_objects() const { return m_dynamic; }
    int frame_count() const { return m_desc.frame_count; }
    /// The animation's segments (docs/design.md): one by default; a new one where the scene file
    /// says, at every frame where an emission or a lamp's intensity differs from the frame before
    /// (a light switched or dimmed), and every frame on its own while an emitter changes size (its
    /// power changes every frame). Within a segment the lights are as bright throughout; lamps,
    /// suns and emitters that move are lit apart (PhotonGroup::moving).
    const std::vector<Segment>& segments() const { return m_segments; }
    const Segment& segment_of(int frame) const;

    /// The camera, object placements, emissions, and lamps and suns at `frame` (any integer;
    /// time is frame / fps).
    FrameState evaluate(int frame) const;
    /// Overrides the output resolution (from --size), keeping everything else.
    void set_resolution(int width, int height);
    /// Leaves the world out of what the camera sees directly (from --transparent-background).
    void set_transparent_background(bool transparent) { m_desc.camera.transparent_background = transparent; }
    /// A sphere holding every object at every frame of the animation: what light from far away
    /// (a sun, the world) is aimed at. One for the whole animation, so that photons from far
    /// away start the same way in every frame (the static and dynamic photon paths agree).
    const BoundingSphere& bounds() const { return m_bounds; }
    /// Where photons of light from far away are aimed when the scene has no portals (found from
    /// the camera's view before rendering: photons/distant_photon_share.h), or null: the whole
    /// disc covering bounds().
    const DistantPhotonTargets* distant_photon_targets() const { return m_distant_targets.get(); }
    void set_distant_photon_targets(std::shared_ptr<const DistantPhotonTargets> targets) {
        m_distant_targets = std::move(targets);
    }

private:
    SceneDesc m_desc;
    std::vector<int> m_static;
    std::vector<int> m_dynamic;
    std::vector<Segment> m_segments;
    BoundingSphere m_bounds;
    std::shared_ptr<const DistantPhotonTargets> m_distant_targets;
};

}  // namespace steadylight
