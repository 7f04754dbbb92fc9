// qhull's reentrant C API behind one function; see qhull_oracle.h.
#include "talus/reference/qhull_oracle.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace talus {
namespace {

// A FILE* that collects qhull's messages in memory, freed on destruction.
class MessageBuffer {
 public:
  MessageBuffer() : m_file(open_memstream(&m_data, &m_size)) {}
  ~MessageBuffer() {
    if (m_file != nullptr) std::fclose(m_file);
    std::free(m_data);
  }
  MessageBuffer(const MessageBuffer&) = delete;
  MessageBuffer& operator=(const MessageBuffer&) = delete;

  [[nodiscard]] FILE* File() const { return m_file; }
  [[nodiscard]] std::string Text() {
    if (m_file == nullptr) return "(no message buffer)";
    std::fflush(m_file);
    return std::string(m_data, m_size);
  }

 private:
  char* m_data = nullptr;
  std::size_t m_size = 0;
  FILE* m_file = nullptr;
};

}  // namespace

namespace {

// Runs qhull with `options` on `points` and hands the finished context to
// `read`, which fills the answer; frees every qhull allocation after.
template <typename T, typename Read>
Result<T> RunQhull(std::span<const Vec3> points, const char* options, Read read) {
  if (points.size() < 4) return Error{"qhull needs at least 4 points, got " + std::to_string(points.size())};
  std::vector<coordT> coordinates;
  coordinates.reserve(3 * points.size());
  for (const Vec3& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});

  MessageBuffer messages;
  qhT context;
  qhT* qh = &context;
  qh_zero(qh, messages.File());
  std::string command = options;
  const int exitCode = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False,
                                    command.data(), nullptr, messages.File());
  Result<T> result = Error{""};
  if (exitCode != 0) {
    result = Error{"qhull failed (exit code " + std::to_string(exitCode) + "): " + messages.Text()};
  } else {
    result = read(qh);
  }
  qh_freeqhull(qh, !qh_ALL);
  int currentLong = 0;
  int totalLong = 0;
  qh_memfreeshort(qh, &currentLong, &totalLong);
  return result;
}

}  // namespace

Result<QhullHull> QhullConvexHull(std::span<const Vec3> points, const QhullOptions& options) {
  return RunQhull<QhullHull>(points, "qhull", [&options](qhT* qh) {
    QhullHull hull;
    vertexT* vertex;
    FORALLvertices { hull.vertexIndices.push_back(qh_pointid(qh, vertex->point)); }
    std::sort(hull.vertexIndices.begin(), hull.vertexIndices.end());
    hull.facetCount = qh->num_facets;
    if (options.computeVolume) {
      qh_getarea(qh, qh->facet_list);
      hull.volume = qh->totvol;
    }
    return hull;
  });
}

Result<std::vector<QhullFacet>> QhullFacets(std::span<const Vec3> points) {
  return RunQhull<std::vector<QhullFacet>>(
      points, "qhull Qt", [](qhT* qh) -> Result<std::vector<QhullFacet>> {
        std::vector<QhullFacet> facets;
        facetT* facet;
        FORALLfacets {
          QhullFacet out;
          out.normal = Vec3(facet->normal[0], facet->normal[1], facet->normal[2]);
          out.offset = facet->offset;
          int corner = 0;
          vertexT* vertex;
          vertexT** vertexp;
          FOREACHvertex_(facet->vertices) {
            if (corner < 3)
              out.corners[static_cast<std::size_t>(corner)] =
                  Vec3(vertex->point[0], vertex->point[1], vertex->point[2]);
            ++corner;
          }
          if (corner != 3)
            return Error{"qhull gave a facet of " + std::to_string(corner) + " vertices after triangulation"};
          facets.push_back(out);
        }
        return facets;
      });
}

}  // namespace talus
