#pragma once
// Depth compositing over MPI ranks (docs/rendering.md, "Over MPI ranks";
// docs/mpi.md): each rank draws the spheres of the particles it owns into a
// layer of its own, multisampled as the frame is; rank 0 writes every
// rank's layer into its frame, sample by sample, with the depth each
// sample's fragment wrote, and draws the rest of the frame (floor, solids,
// ambient occlusion, glass, outlines, overlay) once, on the result.
//
// Same pixels as drawing every sphere on rank 0: the depth test keeps, in
// each sample, the nearest fragment and, among equal depths, the first
// drawn. A rank's layer holds its own nearest-first-drawn fragment per
// sample; rank 0 writes the layers with the same test (less), in the order
// in which the one-process frame draws them: the spheres drawn on squares of
// rank 0, 1, ..., then those on triangles of rank 0, 1, ... (the batch's
// groups, each in memory order, and the ranks own consecutive ranges of it).
// The depth written is the very float the sphere's fragment shader wrote
// (kept per sample in a second colour attachment), which the depth buffer
// turns into the same 24 bits: read back from a depth buffer it would not
// be (llvmpipe's 24-bit depth read as a float and written again changes
// 4.2 M of the 2^24 values; docs/mpi.md, "Rendering over ranks").

#include "render/gl_resources.hpp"
#include "render/rank_compositing.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace sph {

// A layer's textures laid out flat (RankLayerPixels' layout).
struct FlatLayer {
    GLuint colour = 0, depth_bits = 0;
};

// Where a rank draws its spheres: multisampled colour, depth bits and depth,
// then laid out flat to be read back or written into the frame.
class RankLayer {
  public:
    RankLayer(int width, int height, int samples);
    // Binds the layer and clears it: no colour, every sample empty, far.
    void begin();
    // Lays the samples out flat (on the GL).
    void flatten();
    // The flat layer read back (after flatten()).
    void read(RankLayerPixels& out) const;
    FlatLayer flat() const { return {flat_colour_.id(), flat_depth_bits_.id()}; }

  private:
    int width_, height_, samples_;
    gl::Texture colour_, depth_bits_;
    gl::Renderbuffer depth_;
    gl::Framebuffer framebuffer_;
    gl::Texture flat_colour_, flat_depth_bits_;
    gl::Framebuffer flat_framebuffer_;
    gl::Program unpack_;
    gl::VertexArray vao_;
};

// Rank 0's side: the other ranks' layers uploaded, and layers written into
// the bound frame sample by sample.
class LayerImport {
  public:
    LayerImport(int width, int height, int samples);
    // Rank `slot`'s layer on the GL (slots grow as needed).
    FlatLayer upload(std::size_t slot, const RankLayerPixels& layer);
    // Into the bound multisampled frame, with the depth test (less): each
    // layer's samples of one group (0 or triangle_group_bit), in order.
    void draw(std::span<const FlatLayer> layers, std::uint32_t group_bit) const;

  private:
    int width_, height_, samples_;
    std::vector<gl::Texture> colour_, depth_bits_;
    gl::Program program_;
    gl::VertexArray vao_;
};

// Whether a width x height frame of `samples` samples can be laid out flat
// on this context (the flat textures are width x samples wide).
bool layer_fits(int width, int samples);

} // namespace sph
