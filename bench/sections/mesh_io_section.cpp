// Section "mesh-io": loading a simulation frame with clothcd's own readers against assimp (the path every format took
// before), in the same run. The frame is the shared rod-twist step (binary double PLY, 79,864 faces) when the shared
// steps are there (--scalable-ccd, ../shared beside the checkout by default), else a generated cloth of about that size;
// it is also written as ASCII PLY and OBJ (in a temporary folder) to time those readers.
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "../suite/bench_section.hpp"
#include "../suite/bench_util.hpp"
#include "clothcd/mesh/mesh_generators.hpp"
#include "clothcd/mesh/mesh_io.hpp"

namespace clothcd::bench {
namespace {

namespace fs = std::filesystem;

// The peer: assimp's import with the post-processing load_mesh asked of it, and the copy into a TriangleMesh.
TriangleMesh load_with_assimp(const fs::path& path) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
  if (scene != nullptr)
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mNumMeshes == 0) throw std::runtime_error(path.string() + ": assimp cannot read it");
  const aiMesh& mesh = *scene->mMeshes[0];
  TriangleMesh result;
  result.vertices.resize(mesh.mNumVertices, 3);
  for (unsigned v = 0; v < mesh.mNumVertices; ++v)
    result.vertices.row(v) << mesh.mVertices[v].x, mesh.mVertices[v].y, mesh.mVertices[v].z;
  result.faces.resize(mesh.mNumFaces, 3);
  for (unsigned f = 0; f < mesh.mNumFaces; ++f)
    for (unsigned c = 0; c < 3; ++c) result.faces(f, c) = static_cast<int>(mesh.mFaces[f].mIndices[c]);
  return result;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

SectionReport run_mesh_io(const BenchContext& context) {
  const ScratchFolder scratch("mesh-io");
  fs::path frame = context.scalable_ccd ? *context.scalable_ccd / "rod-twist" / "t0.ply" : fs::path();
  std::string source = "the shared rod-twist frame (`scalable-ccd-sample/rod-twist/t0.ply`)";
  if (frame.empty() || !fs::exists(frame)) {
    frame = scratch.path() / "cloth.ply";
    save_mesh(make_grid(201, 201), frame, PlyEncoding::binary_little_endian);
    source = "a generated 201 x 201 cloth (no shared data here)";
  }
  LoadOptions keep_all;  // what load_mesh_frames asks: the file's vertices and faces as they are
  keep_all.join_identical_vertices = false;
  keep_all.drop_degenerate_faces = false;
  const TriangleMesh mesh = load_mesh(frame, keep_all);
  const fs::path ascii = scratch.path() / "frame.ply", obj = scratch.path() / "frame.obj";
  save_mesh(mesh, ascii);
  save_mesh(mesh, obj);

  const int runs = context.quick ? 3 : 21;
  CsvFile csv(context.out_dir / "mesh_io.csv", "file,faces,clothcd_ms,assimp_ms,ratio");
  std::vector<std::vector<std::string>> rows;
  bool met = true;
  for (const auto& [label, path] : {std::make_pair("binary PLY (double)", frame), std::make_pair("ASCII PLY", ascii),
                                    std::make_pair("OBJ", obj)}) {
    context.progress("loading " + std::string(label));
    std::vector<double> ours, theirs;  // alternating, so both see the same machine load
    for (int r = 0; r < runs; ++r) {
      ours.push_back(time_ms([&] { (void)load_mesh(path, keep_all); }));
      theirs.push_back(time_ms([&] { (void)load_with_assimp(path); }));
    }
    const double ours_ms = median(ours), theirs_ms = median(theirs);
    if (label == std::string("binary PLY (double)")) met = ours_ms <= theirs_ms;
    csv.row({csv_text(label), std::to_string(mesh.face_count()), number(ours_ms, 6), number(theirs_ms, 6),
             number(ours_ms / theirs_ms, 4)});
    rows.push_back({label, std::to_string(mesh.face_count()), number(ours_ms, 4), number(theirs_ms, 4),
                    number(ours_ms / theirs_ms, 3)});
  }
  std::string md = "## Mesh loading: clothcd's readers against assimp\n\n";
  md += "Loading " + source + " (" + std::to_string(mesh.vertex_count()) + " vertices, " +
        std::to_string(mesh.face_count()) +
        " faces) as `load_mesh_frames` does (nothing joined or dropped), and the same mesh written as ASCII PLY and OBJ. "
        "clothcd keeps the file's doubles; assimp (the peer: its import, triangulation and the copy into a mesh) "
        "rounds them to float. Median of " + std::to_string(runs) + " runs each, the two alternating, one thread.\n\n";
  md += markdown_table({"file", "faces", "clothcd ms", "assimp ms", "x assimp"}, rows);
  md += "\nTarget (the binary double PLY frame loads no slower than through assimp): " +
        std::string(met ? "**met**" : "**missed**") + ".\n";
  return {md, {"mesh_io.csv"}};
}

const SectionRegistrar registrar{
    {70, "mesh-io", "Loading a simulation frame (binary PLY, ASCII PLY, OBJ): clothcd's readers vs assimp", run_mesh_io}};

}  // namespace
}  // namespace clothcd::bench
