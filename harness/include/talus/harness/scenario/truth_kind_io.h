// What a truth kind's unit (truth_kinds.h) is handed to read its fields from
// a scenario file's truth entry and to write them back.
//
// Every kind declares the same four members beside its fields:
//   static std::string_view Schema();          its fields' JSON-Schema fragment
//   static Result<Kind> Read(TruthReader&);    the file's entry to the kind
//   void Write(TruthWriter&) const;            the kind back to the entry
//   std::vector<MetricResult> Evaluate(const Run&, const Truth&,
//                                      const Trajectory&) const;
// and its name (`static constexpr std::string_view kName`). They are defined
// together in harness/src/truth/kinds/<kind>.cpp; the loader, the writer,
// the evaluator (EvaluateTruth) and the schema (truth_schema.h) reach them
// through the one table, TruthKind.
//
// The entry's fields every kind shares ("kind", "body", "tolerance",
// "gate", "gateReason", "ungated", "published") are read, checked and
// written by the loader and the writer, not by the kinds.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "talus/math.h"
#include "talus/result.h"

namespace talus::harness {

struct BodySpec;
struct WorldSpec;
struct Truth;
struct Run;
struct Trajectory;
struct MetricResult;

/// One truth entry of a scenario file being read: the entry (already valid
/// against the kind's schema, so fields have their types), the scenario's
/// bodies and world (read before the truths), and where the entry sits, for
/// messages that name file and field.
struct TruthReader {
  const nlohmann::json& entry;
  const std::vector<BodySpec>& bodies;
  const std::unordered_map<std::string, int>& bodyIndex;  ///< body index by name
  const WorldSpec& world;
  std::string_view file;
  std::string pointer;  ///< "/truths/<i>"
  int body = -1;        ///< index of the entry's "body", -1 when it names none
  /// The secondary bounds read (Bound), whose written reasons the loader
  /// checks and keeps in Truth::boundReasons.
  std::vector<std::string> bounds{};

  bool Has(const char* field) const;
  double Number(const char* field) const;
  int Integer(const char* field) const;
  std::string Text(const char* field) const;
  Vec3 Vector(const char* field) const;
  /// The value of a secondary bound, written {"value", "reason"} (the
  /// schema requires both); the field is recorded in `bounds`.
  double Bound(const char* field);
  /// The index of the body named `name`, -1 when there is none.
  int FindBody(const std::string& name) const;
  /// Seconds the run lasts: world steps times the time step.
  double Duration() const;
  /// "<file>: <entry's pointer><field>: <problem>": a refusal naming file and field.
  Error Refuse(std::string_view field, std::string_view problem) const;
  /// The same with a pointer from the document's root (e.g. a body's field).
  Error RefuseAt(const std::string& pointer, std::string_view problem) const;
};

/// One truth entry being written: the kind writes its own fields into
/// `out` after "kind" (the writer adds the shared fields after them).
struct TruthWriter {
  nlohmann::ordered_json& out;
  const std::vector<BodySpec>& bodies;
  const Truth& truth;

  /// Writes a secondary bound as {"value", "reason"}, the reason the truth
  /// keeps for it (empty for a truth built in code).
  void Bound(const char* field, double value);
  /// The array [x, y, z].
  void Vector(const char* field, const Vec3& value);
};

/// |v| without overflow or underflow for any finite v (1e300 or 1e-300
/// components): the largest component is factored out first.
double ScaleSafeNorm(const Vec3& v);

/// v / |v| computed as above; zero for a zero vector.
Vec3 ScaleSafeNormalized(const Vec3& v);

}  // namespace talus::harness
