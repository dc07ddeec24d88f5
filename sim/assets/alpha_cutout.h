#pragma once
// MuJoCo 2.2 draws textures opaque (it reads RGB only and never alpha-tests),
// so a hair mesh made of alpha-masked cards renders as a solid cap and eye
// meshes cover the face. The choice here: cut, not composite. Triangles of
// alpha-masked materials are dropped where the texture is mostly transparent
// over them, and the colour of the remaining transparent texels is replaced
// by the material's mean opaque colour, so the parts of kept triangles that
// should be see-through show hair-coloured texels instead of the black or
// white an exporter left there. Compositing the hair over the skin texture
// instead would need the skin's UVs under each card, which do not exist.
#include "sim/assets/asset_model.h"

namespace depot::sim {

// Mean texture alpha (0..1) over a triangle, sampled at its corners, edge
// midpoints and centroid (nearest texel, UVs wrapped). 1 without texture
// alpha or UVs.
float triangle_alpha(const AssetMesh& mesh, const AssetMaterial& material, int triangle);

// For every alpha-masked material with texture alpha: drops the triangles
// whose triangle_alpha is below the material's alpha_cutoff (then the
// vertices no triangle uses), and fills the transparent texels' colour.
// Returns the number of triangles dropped.
int cut_alpha_triangles(AssetModel& model);

}  // namespace depot::sim
