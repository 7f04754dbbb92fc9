// The backend registry and the world measures derived from body states
// (see talus/harness/backend/backend.h).
#include "talus/harness/backend/backend.h"

#include <cassert>

namespace talus::harness {

void BackendRegistry::Register(std::string name, std::string description, ThreadSafety safety,
                               BackendFactory factory) {
  assert(!m_entries.contains(name) && "backend registered twice");
  m_entries.emplace(std::move(name), Entry{std::move(description), std::move(safety), std::move(factory)});
}

std::vector<std::string> BackendRegistry::Names() const {
  std::vector<std::string> names;
  for (const auto& [name, entry] : m_entries) names.push_back(name);
  return names;
}

bool BackendRegistry::Has(std::string_view name) const { return m_entries.find(name) != m_entries.end(); }

std::string BackendRegistry::Description(std::string_view name) const {
  const auto it = m_entries.find(name);
  return it == m_entries.end() ? std::string() : it->second.description;
}

ThreadSafety BackendRegistry::GetThreadSafety(std::string_view name) const {
  const auto it = m_entries.find(name);
  return it == m_entries.end() ? ThreadSafety::Independent() : it->second.safety;
}

Result<std::unique_ptr<Backend>> BackendRegistry::Create(std::string_view name, const Run& run) const {
  const auto it = m_entries.find(name);
  if (it == m_entries.end()) {
    std::string known;
    for (const auto& [key, entry] : m_entries) known += (known.empty() ? "" : ", ") + key;
    return Error{"unknown backend \"" + std::string(name) + "\" (known: " + known + ")"};
  }
  return it->second.factory(run);
}

WorldMeasures MeasureWorld(const Backend& backend, const Vec3& gravity) {
  WorldMeasures measures;
  for (int i = 0; i < backend.BodyCount(); ++i) {
    const BodyReading state = backend.GetBodyState(i);
    if (state.mass <= 0.0) continue;
    const Vec3 momentum = state.mass * state.linearVelocity;
    const Vec3 spin = state.worldInertia * state.angularVelocity;
    measures.kineticEnergy +=
        0.5 * state.mass * state.linearVelocity.squaredNorm() + 0.5 * state.angularVelocity.dot(spin);
    measures.potentialEnergy -= state.mass * gravity.dot(state.centerOfMass);
    measures.linearMomentum += momentum;
    measures.angularMomentum += state.centerOfMass.cross(momentum) + spin;
  }
  return measures;
}

}  // namespace talus::harness
