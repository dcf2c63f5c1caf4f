#include "fcl_peer.hpp"

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

namespace clothcd::bench {

std::vector<fcl::Vector3d> fcl_points(const Vertices& v) {
  std::vector<fcl::Vector3d> p(static_cast<std::size_t>(v.rows()));
  for (Eigen::Index i = 0; i < v.rows(); ++i) p[static_cast<std::size_t>(i)] = v.row(i).transpose();
  return p;
}

std::shared_ptr<FclModel> fcl_model(const TriangleMesh& mesh, const Vertices& positions) {
  std::vector<fcl::Triangle> triangles(static_cast<std::size_t>(mesh.face_count()));
  for (Eigen::Index f = 0; f < mesh.face_count(); ++f)
    triangles[static_cast<std::size_t>(f)] = fcl::Triangle(mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2));
  auto model = std::make_shared<FclModel>();
  model->beginModel();
  model->addSubModel(fcl_points(positions), triangles);
  model->endModel();
  return model;
}

std::size_t fcl_refit_and_collide(const std::shared_ptr<FclModel>& model, const std::vector<fcl::Vector3d>& positions,
                                  const std::shared_ptr<FclModel>& other) {
  model->beginUpdateModel();
  model->updateSubModel(positions);
  model->endUpdateModel(true, true);
  fcl::CollisionObjectd a(model), b(other);
  fcl::CollisionRequestd request(100000000, false);
  fcl::CollisionResultd result;
  fcl::collide(&a, &b, request, result);
  return result.numContacts();
}

}  // namespace clothcd::bench
