// Bad assets through the command line: a scenario drawing its actors from a
// user's asset catalogue (`asset_catalog`, mesh style) whose model file is
// missing, corrupt, of an unsupported format or without faces, whose texture
// is missing, whose clip does not exist, or which names an unknown class gets
// one error line naming the file and the problem, a non-zero exit and no
// dataset.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/support/cli_checks.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace fs = std::filesystem;

namespace depot::test {
namespace {

const std::string kWorker = std::string(DEPOT_SHARED_DATA) + "/assets/people/mh_worker_male.glb";

// A catalogue with one person entry made of `entry` lines (indented 4).
std::string catalogue(const std::string& name, const std::string& entry) {
  return write_yaml(name, "assets:\n  someone:\n" + entry);
}

// Writes `text` to `name` in a fresh folder per test (files of one model,
// e.g. an OBJ and its MTL, share the test's folder).
std::string file_with(const std::string& name, const std::string& text) {
  static const std::string folder = [] {
    const std::string dir = temp_path("models");
    fs::create_directories(dir);
    return dir;
  }();
  const std::string path = folder + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Renders depot_walking_xyz with mesh actors from `catalog`; expects a clean
// failure whose one line names every needle.
void expect_asset_failure(const std::string& catalog, const std::vector<std::string>& needles) {
  const std::string out = temp_path("out");
  DepotResult r = depot(
      "sim render depot_walking_xyz --frames 2 --width 64 --set actors_style=mesh"
      " --set asset_catalog=" +
      catalog + " -q -o " + out);
  expect_one_error_line(r, needles);
  EXPECT_FALSE(fs::exists(out)) << "no dataset on failure";
  for (const auto& e : fs::directory_iterator(fs::path(out).parent_path()))
    EXPECT_EQ(e.path().filename().string().find(fs::path(out).filename().string() + ".partial"),
              std::string::npos);
}

TEST(CliAssets, MissingModelFile) {
  const std::string missing = temp_path("nowhere") + "/person.glb";
  expect_asset_failure(catalogue("missing", "    file: " + missing + "\n    class: person\n"),
                       {missing, "not found"});
}

TEST(CliAssets, CorruptModelFile) {
  const std::string glb = file_with("corrupt.glb", "glTF this is not a binary glTF at all");
  expect_asset_failure(catalogue("corrupt", "    file: " + glb + "\n    class: person\n"), {glb});
}

TEST(CliAssets, UnsupportedFormat) {
  const std::string txt = file_with("person.txt", "a person\n");
  expect_asset_failure(catalogue("format", "    file: " + txt + "\n    class: person\n"),
                       {txt, "unsupported format"});
}

TEST(CliAssets, ModelWithoutFaces) {
  const std::string obj = file_with("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expect_asset_failure(catalogue("faces", "    file: " + obj + "\n    class: person\n"), {obj});
}

TEST(CliAssets, MissingTexture) {
  const std::string obj = file_with("textured.obj",
                                    "mtllib textured.mtl\nusemtl skin\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                    "vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  file_with("textured.mtl", "newmtl skin\nKd 1 1 1\nmap_Kd no_such_texture.png\n");
  expect_asset_failure(catalogue("texture", "    file: " + obj + "\n    class: person\n"),
                       {"no_such_texture.png"});
}

TEST(CliAssets, ClipThatDoesNotExist) {
  expect_asset_failure(catalogue("clip", "    file: " + kWorker +
                                             "\n    class: person\n    up: +y\n    forward: +z\n"
                                             "    clips: {walk: Moonwalk}\n"),
                       {"Moonwalk", "someone"});
}

TEST(CliAssets, UnknownClass) {
  expect_asset_failure(catalogue("class", "    file: " + kWorker + "\n    class: dragon\n"),
                       {"dragon", "someone"});
}

}  // namespace
}  // namespace depot::test
