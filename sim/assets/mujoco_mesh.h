#pragma once
// A loaded model as MuJoCo 2.2.2 assets: binary meshes (.msh) and PNG
// textures for the scene's in-memory VFS, the <mesh>/<texture>/<material>
// elements that name them, and per-frame vertex updates of a compiled model.
//
// MuJoCo 2.2 moves every mesh into its inertial frame when it compiles it
// (vertices re-centred on the centre of mass and rotated onto the principal
// axes, user_mesh.cc Process()) and moves the geom by the same amount
// (geom_pos/geom_quat relative to its body absorb it). So model->mesh_vert
// holds vertices in the *geom* frame, not in the frame they were written in.
// A skinned actor deforms its vertices in the model frame (= the frame of
// the mocap body that carries the geoms) and must map them into each geom's
// frame before writing mesh_vert/mesh_normal and calling mjr_uploadMesh:
//   v_geom = geom_quat^-1 * (v_body - geom_pos)
// which write_mesh_vertices() does. (Equivalently, from world vertices:
// geom_xmat^T * (v_world - geom_xpos).) The compiler keeps the vertex count
// and order of a .msh file, so vertex i of the file is mesh_vert i.
#include <mujoco/mujoco.h>

#include <string>
#include <utility>
#include <vector>

#include "sim/assets/asset_model.h"

namespace depot::sim {

// MuJoCo's binary mesh file, as mjCMesh::LoadMSH reads it (little-endian):
//   int32 nvertex, nnormal, ntexcoord, nface
//   float32 vertex[3 nvertex], normal[3 nnormal], texcoord[2 ntexcoord]
//   int32 face[3 nface]
// nnormal and ntexcoord are 0 or nvertex; MuJoCo wants nvertex >= 4. UVs are
// written as given (top-left origin, what MuJoCo samples). Fails naming
// `where` for fewer than 4 vertices, mismatched arrays or a bad index.
std::string encode_msh(const std::vector<Eigen::Vector3f>& positions,
                       const std::vector<Eigen::Vector3f>& normals,
                       const std::vector<Eigen::Vector2f>& uvs,
                       const std::vector<Eigen::Vector3i>& triangles, const std::string& where);
std::string encode_msh(const AssetMesh& mesh, const std::string& where);

// PNG bytes of a texture for <texture type="2d" file=...>: 3 channels, since
// MuJoCo 2.2 keeps RGB only.
std::string encode_texture_png(const cv::Mat& image);

// Everything a scene builder adds to its MJCF for one model.
struct MujocoAssetSet {
  std::vector<std::pair<std::string, std::string>> files;  // VFS name -> bytes
  std::string asset_xml;                                   // elements for <asset>
  std::vector<std::string> mesh_names;                     // per AssetModel::meshes
  std::vector<std::string> material_names;                 // per AssetModel::meshes ("" for none)
};

// Names start with `prefix` (unique per model in a scene, e.g. "worker0").
// Meshes are encoded at the bind pose; materials carry the base colour and
// the texture, with no specular (like the depot's own materials).
MujocoAssetSet encode_for_mujoco(const AssetModel& model, const std::string& prefix);

// One <geom type="mesh"> per mesh of the set, visual only (no contacts),
// `extra` appended inside each element (e.g. group="1").
std::string mesh_geoms_xml(const MujocoAssetSet& set, const std::string& extra = "");

// The compiled geom's frame in its body's frame (geom_pos, geom_quat): where
// MuJoCo moved the mesh's inertial frame to.
Eigen::Isometry3d geom_in_body(const mjModel* m, int geom);

// Writes deformed vertices and normals, given in the frame of the geom's
// body, into the compiled mesh of mesh geom `geom` (mapped into the geom's
// frame). Call mjr_uploadMesh(m, con, m->geom_dataid[geom]) afterwards for
// the renderer to see them. Fails when the geom is not a mesh or the counts
// differ from the compiled mesh's.
void write_mesh_vertices(mjModel* m, int geom, const std::vector<Eigen::Vector3f>& positions,
                         const std::vector<Eigen::Vector3f>& normals);

}  // namespace depot::sim
