#pragma once
// The bricks the raymarch skips empty space with: volume_bricks' value ranges and largest alpha
// per brick, then volume_brick_skip's three passes, which give each brick its stride: how many
// bricks around it are of its kind (empty or occupied), so that a ray crosses them with one
// lookup instead of one per brick.
#include "engine/kernels/backend.h"

namespace masav::volume {

// The farthest stride looked for, in bricks. A ray then crosses up to 2 x 16 - 1 bricks of one
// kind per lookup; the transform reads 2 radius + 1 bricks per brick and pass.
constexpr uint32_t kBrickSkipRadius = 16;

// Fills bricks (brick_dims(p.volume, p.brick) of them) for p's volume and transfer function, with
// strides looked for up to `radius` bricks away (1: every brick alone).
void fill_bricks(Backend& b, const VolumeBrickParams& p, const Buffer<Real>& volume,
                 const Buffer<Real4>& tf, Buffer<Real4>& bricks,
                 uint32_t radius = kBrickSkipRadius);

}  // namespace masav::volume
