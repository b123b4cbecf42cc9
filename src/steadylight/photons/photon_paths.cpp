// Static photon paths kept and composed into each frame's maps (photon_paths.h).
#include "steadylight/photons/photon_paths.h"

#include <numeric>

#include "steadylight/base/check.h"
#include "steadylight/base/parallel.h"
#include "steadylight/photons/photon_tracer.h"

namespace steadylight {
namespace {

// Paths per chunk of the parallel loops; chunks join in order, so results do not depend on threads.
constexpr long chunk = 4096;

size_t chunks_of(long count) { return size_t((count + chunk - 1) / chunk); }

/// Whether photons of `kind` are traced at all in `context` (as trace_photons decides).
long path_count(const FrameContext& context, const PhotonSettings& settings, MapKind kind) {
    if (context.lights.empty()) return 0;
    if (kind == MapKind::global) return settings.global_photons;
    return has_non_diffuse_surface(context) ? settings.caustic_photons : 0;
}

/// Turns per-path counts into offsets: first[i] = sum of counts before i, with one more at the end.
std::vector<uint32_t> offsets_of(const std::vector<uint32_t>& counts) {
    std::vector<uint32_t> first(counts.size() + 1, 0);
    for (size_t i = 0; i < counts.size(); ++i) first[i + 1] = first[i] + counts[i];
    return first;
}

StoredPaths trace_stored(const FrameContext& context, const PhotonSettings& settings, MapKind kind) {
    StoredPaths paths;
    // The static scene holds the still lights' paths; a moving light's are traced every frame.
    const PhotonSplit split = context.lights.split(path_count(context, settings, kind));
    paths.count = split.still;
    if (kind == MapKind::caustic) paths.targets.emplace(context, Visibility::static_only);
    if (paths.count <= 0) {
        paths.first_segment = paths.first_photon = {0};
        return paths;
    }
    const size_t chunks = chunks_of(paths.count);
    std::vector<std::vector<Photon>> photons(chunks);
    std::vector<std::vector<PathSegment>> segments(chunks);
    std::vector<uint32_t> segment_counts(size_t(paths.count)), photon_counts(size_t(paths.count));
    const PhotonTracer tracer(context, settings, kind, Visibility::static_only,
                              paths.targets ? &*paths.targets : nullptr);
    const float scale = 1.0f / float(paths.count);
    parallel_for_chunks(paths.count, chunk, [&](long begin, long end) {
        const size_t c = size_t(begin / chunk);
        const PhotonOutput out{photons[c], nullptr, true, &segments[c]};
        for (long i = begin; i < end; ++i) {
            const size_t photons_before = photons[c].size(), segments_before = segments[c].size();
            tracer.trace(first_photon_index(kind) + uint64_t(i), PhotonGroup::still, scale, out);
            photon_counts[size_t(i)] = uint32_t(photons[c].size() - photons_before);
            segment_counts[size_t(i)] = uint32_t(segments[c].size() - segments_before);
        }
    });
    paths.first_segment = offsets_of(segment_counts);
    paths.first_photon = offsets_of(photon_counts);
    paths.segments = join(segments);
    paths.photons = PhotonMap(join(photons), paths.count);
    return paths;
}

/// A path that meets a dynamic object in this frame: from which of its rays on, and what it
/// does from there (in its chunk's vectors).
struct ChangedPath {
    uint32_t path;
    int bounce;                                               // its first ray that meets a dynamic object
    size_t main_begin, main_end, dynamic_begin, dynamic_end;  // its new photons
};

/// The changed paths of one chunk and their new photons.
struct ChunkChanges {
    std::vector<ChangedPath> paths;
    std::vector<Photon> main, dynamic;
};

/// The first ray of path `i` that meets a dynamic object at this frame, if any.
std::optional<int> first_dynamic_ray(const RayTracer& tracer, const StoredPaths& paths, size_t i) {
    for (uint32_t s = paths.first_segment[i]; s < paths.first_segment[i + 1]; ++s) {
        const PathSegment& segment = paths.segments[s];
        if (tracer.meets_dynamic(Ray{segment.o, segment.d}, segment.t_static)) return int(s - paths.first_segment[i]);
    }
    return std::nullopt;
}

/// Finds the paths that meet a dynamic object and retraces them from there.
std::vector<ChunkChanges> retrace_changed(const FrameContext& context, const PhotonSettings& settings,
                                          const StoredPaths& paths, MapKind kind, bool dynamic_map) {
    std::vector<ChunkChanges> changes(chunks_of(paths.count));
    const PhotonTracer tracer(context, settings, kind, Visibility::everything,
                              paths.targets ? &*paths.targets : nullptr);
    parallel_for_chunks(paths.count, chunk, [&](long begin, long end) {
        ChunkChanges& mine = changes[size_t(begin / chunk)];
        // The negative photons are the static path's own later photons: taken from there.
        const PhotonOutput out{mine.main, dynamic_map ? &mine.dynamic : nullptr, false};
        for (long i = begin; i < end; ++i) {
            const std::optional<int> bounce = first_dynamic_ray(context.tracer, paths, size_t(i));
            if (!bounce) continue;
            ChangedPath changed{uint32_t(i), *bounce, mine.main.size(), 0, mine.dynamic.size(), 0};
            tracer.resume(first_photon_index(kind) + uint64_t(i),
                          paths.segments[paths.first_segment[size_t(i)] + uint32_t(*bounce)], *bounce, out);
            changed.main_end = mine.main.size();
            changed.dynamic_end = mine.dynamic.size();
            mine.paths.push_back(changed);
        }
    });
    return changes;
}

/// Where a map's photons come from, as it is composed.
struct Composition {
    std::vector<Photon> photons;
    KeptStaticPhotons kept;
};

/// The static photons of a changed path that stay: those stored before its first dynamic ray.
uint32_t kept_end(const StoredPaths& paths, const ChangedPath& changed) {
    const std::vector<Photon>& photons = paths.photons.photons();
    uint32_t end = paths.first_photon[changed.path];
    while (end < paths.first_photon[changed.path + 1] && photons[end].bounce < changed.bounce) ++end;
    return end;
}

/// The main map in full tracing's order: each path's static photons, a changed path's only up
/// to its first dynamic ray and then its new ones.
Composition compose_main(const StoredPaths& paths, const std::vector<ChunkChanges>& changes) {
    const std::vector<Photon>& base = paths.photons.photons();
    Composition c;
    c.kept.frame_ids.assign(base.size(), PointIndex::removed);
    c.photons.reserve(base.size());
    uint32_t cursor = 0;
    const auto keep = [&](uint32_t end) {
        if (end <= cursor) return;
        const uint32_t first = uint32_t(c.photons.size());
        std::iota(c.kept.frame_ids.begin() + cursor, c.kept.frame_ids.begin() + end, first);
        c.photons.insert(c.photons.end(), base.begin() + cursor, base.begin() + end);
        cursor = end;
    };
    for (const ChunkChanges& chunk_changes : changes)
        for (const ChangedPath& changed : chunk_changes.paths) {
            keep(kept_end(paths, changed));
            for (size_t i = changed.main_begin; i < changed.main_end; ++i) {
                c.kept.added_ids.push_back(uint32_t(c.photons.size()));
                c.photons.push_back(chunk_changes.main[i]);
            }
            cursor = paths.first_photon[changed.path + 1];
        }
    keep(uint32_t(base.size()));
    return c;
}

/// The dynamic map in full tracing's order: per changed path, its negative photons (the static
/// path's photons from the first dynamic ray on, power negated, direct hits and caustic photons
/// left out as the tracer leaves them out: a photon is caustic when the ray that brought it
/// followed only specular bounces), then its new ones.
std::vector<Photon> compose_dynamic(const StoredPaths& paths, const std::vector<ChunkChanges>& changes) {
    const std::vector<Photon>& base = paths.photons.photons();
    std::vector<Photon> dynamic;
    for (const ChunkChanges& chunk_changes : changes)
        for (const ChangedPath& changed : chunk_changes.paths) {
            const PathSegment* rays = paths.segments.data() + paths.first_segment[changed.path];
            for (uint32_t i = kept_end(paths, changed); i < paths.first_photon[changed.path + 1]; ++i)
                if (base[i].bounce > 0 && !rays[base[i].bounce].specular_path) {
                    Photon negative = base[i];
                    negative.power = base[i].power * -1.0f;
                    dynamic.push_back(negative);
                }
            dynamic.insert(dynamic.end(), chunk_changes.dynamic.begin() + long(changed.dynamic_begin),
                           chunk_changes.dynamic.begin() + long(changed.dynamic_end));
        }
    return dynamic;
}

/// Where a composition over `base` removed its photons and added new ones.
std::vector<Vec3> changed_points(const PhotonMap& base, const Composition& c) {
    std::vector<Vec3> points;
    for (size_t i = 0; i < c.kept.frame_ids.size(); ++i)
        if (c.kept.frame_ids[i] == PointIndex::removed) points.push_back(base.photons()[i].p);
    for (const uint32_t i : c.kept.added_ids) points.push_back(c.photons[i].p);
    return points;
}

/// Adds the moving lights' paths [split.still, split.total), traced in the frame, after the
/// still ones, as full tracing orders them: their photons to `main` as new ones, and theirs to
/// `dynamic`, all of which is change.
void add_moving_paths(const FrameContext& context, const StoredPaths& paths, const PhotonSettings& settings,
                      MapKind kind, PhotonSplit split, bool dynamic_map, Composition& main,
                      std::vector<Photon>* dynamic) {
    if (split.count(PhotonGroup::moving) == 0) return;
    SL_CHECK(split.still == paths.count);  // the frame splits its paths as its segment's static pass did
    const PhotonTracer tracer(context, settings, kind, Visibility::everything,
                              paths.targets ? &*paths.targets : nullptr);
    TracedPaths moving = trace_paths(tracer, kind, split, split.still, split.total, dynamic_map);
    for (const Photon& photon : moving.main) {
        main.kept.added_ids.push_back(uint32_t(main.photons.size()));
        main.photons.push_back(photon);
    }
    if (dynamic) dynamic->insert(dynamic->end(), moving.dynamic.begin(), moving.dynamic.end());
}

long changed_count(const std::vector<ChunkChanges>& changes) {
    long count = 0;
    for (const ChunkChanges& chunk_changes : changes) count += long(chunk_changes.paths.size());
    return count;
}

}  // namespace

size_t StoredPaths::bytes() const {
    return (first_segment.size() + first_photon.size()) * sizeof(uint32_t) + segments.size() * sizeof(PathSegment) +
           photons.size() * sizeof(Photon);
}

StaticPhotonPaths trace_static_photon_paths(const FrameContext& context, const PhotonSettings& settings) {
    return {settings, trace_stored(context, settings, MapKind::global),
            trace_stored(context, settings, MapKind::caustic)};
}

ComposedPhotons compose_photons(const FrameContext& context, const StaticPhotonPaths& paths) {
    ComposedPhotons out;
    const StoredPaths& global = paths.global;
    // As trace_photons: the dynamic map comes from the global paths, where something moves.
    const bool dynamic = has_dynamic_map(context);
    const PhotonSplit global_split = context.lights.split(path_count(context, paths.settings, MapKind::global));
    const std::vector<ChunkChanges> global_changes =
        retrace_changed(context, paths.settings, global, MapKind::global, dynamic);
    Composition composed = compose_main(global, global_changes);
    std::vector<Photon> dynamic_photons = compose_dynamic(global, global_changes);
    add_moving_paths(context, global, paths.settings, MapKind::global, global_split, dynamic, composed,
                     &dynamic_photons);
    out.maps.global = PhotonMap(std::move(composed.photons), global_split.total, global.photons, composed.kept);
    out.global_kept = std::move(composed.kept);
    out.maps.dynamic = PhotonMap(std::move(dynamic_photons), dynamic ? global_split.total : 0);
    out.retraced_paths = changed_count(global_changes) + global_split.count(PhotonGroup::moving);

    const StoredPaths& caustic = paths.caustic;
    if (caustic.count > 0 && !(CausticTargets(context, Visibility::everything) == *caustic.targets)) {
        PhotonSettings caustic_only = paths.settings;
        caustic_only.global_photons = 0;
        out.maps.caustic = std::move(trace_photons(context, caustic_only).caustic);
        out.caustic_traced = true;
        return out;
    }
    const PhotonSplit caustic_split = context.lights.split(path_count(context, paths.settings, MapKind::caustic));
    const std::vector<ChunkChanges> caustic_changes =
        retrace_changed(context, paths.settings, caustic, MapKind::caustic, false);
    composed = compose_main(caustic, caustic_changes);
    add_moving_paths(context, caustic, paths.settings, MapKind::caustic, caustic_split, false, composed, nullptr);
    out.changed_caustic_points = changed_points(caustic.photons, composed);
    out.maps.caustic = PhotonMap(std::move(composed.photons), caustic_split.total, caustic.photons, composed.kept);
    out.caustic_retraced_paths = changed_count(caustic_changes) + caustic_split.count(PhotonGroup::moving);
    out.retraced_paths += out.caustic_retraced_paths;
    return out;
}

}  // namespace steadylight
