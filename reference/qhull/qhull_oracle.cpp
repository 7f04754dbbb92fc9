// qhull's reentrant C API behind one function; see qhull_oracle.h.
#include "talus/reference/qhull_oracle.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

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

Result<QhullHull> QhullConvexHull(std::span<const Vec3> points, const QhullOptions& options) {
  if (points.size() < 4) return Error{"qhull needs at least 4 points, got " + std::to_string(points.size())};
  std::vector<coordT> coordinates;
  coordinates.reserve(3 * points.size());
  for (const Vec3& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});

  MessageBuffer messages;
  qhT context;
  qhT* qh = &context;
  qh_zero(qh, messages.File());
  char command[] = "qhull";
  const int exitCode = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False,
                                    command, nullptr, messages.File());
  Result<QhullHull> result = Error{""};
  if (exitCode != 0) {
    result = Error{"qhull failed (exit code " + std::to_string(exitCode) + "): " + messages.Text()};
  } else {
    QhullHull hull;
    vertexT* vertex;
    FORALLvertices { hull.vertexIndices.push_back(qh_pointid(qh, vertex->point)); }
    std::sort(hull.vertexIndices.begin(), hull.vertexIndices.end());
    hull.facetCount = qh->num_facets;
    if (options.computeVolume) {
      qh_getarea(qh, qh->facet_list);
      hull.volume = qh->totvol;
    }
    result = std::move(hull);
  }
  qh_freeqhull(qh, !qh_ALL);
  int currentLong = 0;
  int totalLong = 0;
  qh_memfreeshort(qh, &currentLong, &totalLong);
  return result;
}

}  // namespace talus
