// The frame a job renders, posed with the frames before and after it when the motion AOV is
// asked for (render/motion_vectors.h). Internal to the job layer.
#pragma once

#include <memory>
#include <vector>

#include "io/gltf/gltf_loader.h"
#include "job/render_job.h"

namespace kiln {

// The seconds between the job's frame and its neighbours: one frame at --fps (default 24), also
// when the time was given with --time.
double motion_frame_seconds(const render_options& options);

// The first call for an animated file seen by the default camera or an orbit view also finds
// p.framing, the bounds of its poses across the animation. Poses asset at the job's time into p.world
// (previous: the scene the asset's last pose returned, or null; posed: the meshes built for this time). With
// the motion AOV asked for, first poses the times one frame before and after and keeps in p.motion what they
// place where, with their cameras; finish_loaded_scene adds the frame's own pose. A file without animation
// does not move: its neighbours are the frame itself.
void pose_job_frame(gltf_sequence& asset, const render_options& options, scene* previous,
                    std::vector<uint32_t>* posed, prepared_scene& p);

}  // namespace kiln
