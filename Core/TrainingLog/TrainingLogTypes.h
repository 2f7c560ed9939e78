// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TrainingLogTypes.h
 * @brief In-memory form of the training log's tables (DESIGN §3, format version 1).
 */
#ifndef vis4gs_TrainingLogTypes_h
#define vis4gs_TrainingLogTypes_h

#include <cstdint>
#include <vector>

namespace vis4gs
{

/// Densification event kinds as stored in /events/kind.
enum class EventKind : std::uint8_t
{
  Clone = 1,
  Split = 2,
  Prune = 3
};

/// One row of /events: rows are kept in the order the trainer did them.
struct TrainingEvent
{
  std::int32_t Iteration = 0;
  EventKind Kind = EventKind::Clone;
  std::int64_t Parent = -1; ///< GaussianId
  std::int64_t Child = -1;  ///< GaussianId, -1 for prune
};

/// Columns of /events as structure of arrays (what readers return for large logs).
struct EventTable
{
  std::vector<std::int32_t> Iteration;
  std::vector<std::uint8_t> Kind;
  std::vector<std::int64_t> Parent;
  std::vector<std::int64_t> Child;

  std::size_t Size() const { return this->Iteration.size(); }
};

} // namespace vis4gs

#endif
