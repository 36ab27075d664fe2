#include "experiments/common/point_json.h"

namespace cmt {

nlohmann::json point_json(const Vec3& p, int dimension) {
  if (dimension == 2) return nlohmann::json::array({p.x(), p.z()});
  return nlohmann::json::array({p.x(), p.y(), p.z()});
}

}  // namespace cmt
