// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Genealogy.h
 * @brief The densification tree (genealogy) of a training run, built from the training
 * log's events (DESIGN §3, §4): nodes, families, descendant counts, lifespans, perception
 * values, the tree layout and the family bands, plus lineage queries and the root-cause trace.
 *
 * Everything is stored in compact arrays indexed by a *node index* 0..N-1 (one node per
 * Gaussian that ever lived). Node indices follow creation order: the initial Gaussians first
 * (in the order given), then one node per birth event in event order (after sorting, see
 * below); repaired orphan roots are inserted just before the first event that names them.
 * Hence Parent(i) < i for every non-root node, and children are listed in creation order.
 *
 * Definitions (summarised in Core/Genealogy/README.md):
 * - **BirthIteration**: 0-based iteration of the event that created the node; initial
 *   Gaussians are born at iteration 0 (or at the iteration passed to Build).
 * - **DeathIteration**: iteration of the split or prune that ended the node; **-1 while
 *   alive** at the last logged iteration. A split ends its parent (Pruned stays 0); a
 *   prune ends a Gaussian (Pruned = 1). A clone never ends its parent.
 * - **Lifespan T** = End - Birth with End = DeathIteration, or the last logged iteration for
 *   a Gaussian still alive. Zero-lifespan nodes (born and ended in the same iteration or
 *   interval) are legal and have T = 0.
 * - **Descendant count D**: number of proper descendants (children, grandchildren, ...).
 * - **Family**: a root and all its descendants. FamilyId is the index of the family's row in
 *   the family bands table (families are numbered by their root's node index order).
 * - **Perception value P** (DESIGN §4, exact): P = a*D/max_F D + (1-a)*T/max_F T with
 *   a = Alpha = 0.4, maxima over the node's family; a zero denominator makes its term 0.
 * - **Layout**: LayoutX = BirthIteration. LayoutY = a row unique over the whole tree: within a
 *   family, rows follow a pre-order traversal that visits children in creation (branch)
 *   order, so the root gets the family's first row, its first-born child the next row, the
 *   whole subtree of that child the following D+1 rows, then the second-born child, and so
 *   on. A node's subtree therefore occupies the contiguous rows [row, row + D]. Families are
 *   stacked in FamilyId order without overlap: family f starts at the row after the last row
 *   of family f-1 (rows 0..N-1 are all used exactly once).
 * - **Family band**: iteration range [root birth, max End over the family] and row range
 *   [first row, last row] (both inclusive) of a family.
 *
 * Event semantics (fine mode, CoarsenInterval = 0): a clone row (parent, child) adds a
 * child, the parent lives on; a split row (parent, child) adds a child and ends the parent
 * at that iteration (several split rows of one parent at the same iteration are one split);
 * a prune row (parent, -1) ends that Gaussian. An event naming a Gaussian that has already
 * ended (earlier split or prune) is an error.
 *
 * Coarsening (CoarsenInterval = I > 0): every event iteration t is mapped to the end of its
 * logging interval, ceil(t / I) * I (the first snapshot that can show its effect), and the
 * order of events inside one interval no longer matters. A parent that both cloned and
 * split within one interval becomes one clone-split node: all children it produced in that
 * interval get BirthKind::CloneSplit (and edge kind clone-split), the parent is one node
 * that stays alive through the interval and ends at its recorded death (the interval of its
 * split). An event naming a Gaussian that ended in an earlier interval is an error.
 *
 * Bad input (all with messages naming the event row as stored in the table, 0-based):
 * - columns of different lengths, unknown kind, negative ids, a prune with a child id, an
 *   iteration < 0: error (std::runtime_error).
 * - events out of order (iteration decreasing): by default sorted stably by iteration, with
 *   a warning in GetWarnings(); with StrictEventOrder an error naming the first such row.
 * - unknown parent: error; with RepairUnknownParents an orphan root is created for it
 *   (BirthKind::Root, born at the iteration of the first event naming it) and listed in
 *   GetOrphanRoots() and GetWarnings().
 * - a Gaussian born twice (a child id that already exists, or a repeated initial id):
 *   error; with RepairDuplicateBirths the later birth row is dropped (listed in
 *   GetDroppedEventRows() and GetWarnings(); repeated initial ids are kept once).
 * - last iteration before an event's iteration: error (pass a negative last iteration to use
 *   the largest event iteration).
 *
 * Complexity: O(N + E) time and memory (plus O(E log E) only when events must be sorted);
 * every traversal is iterative (chains of any depth, families of any size).
 */
#ifndef vis4gs_Genealogy_h
#define vis4gs_Genealogy_h

#include "TrainingLogTypes.h"

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vis4gs
{

/// How a node was born. Values 1 and 2 match EventKind; 3 (prune) is never a birth kind.
enum class BirthKind : std::uint8_t
{
  Root = 0,
  Clone = 1,
  Split = 2,
  CloneSplit = 4
};

/// Name of a birth kind ("root", "clone", "split", "clone-split").
const char* BirthKindName(BirthKind kind);

/// Options of Genealogy::Build.
struct GenealogyOptions
{
  /// Coarsen events to this logging interval (iterations); 0 keeps events as logged.
  std::int32_t CoarsenInterval = 0;
  /// Events out of order: false sorts them stably by iteration with a warning, true is an error.
  bool StrictEventOrder = false;
  /// Unknown parent: false is an error, true creates an orphan root for it.
  bool RepairUnknownParents = false;
  /// Gaussian born twice: false is an error, true drops the later birth row.
  bool RepairDuplicateBirths = false;
  /// Weight of the descendant term in the perception value (DESIGN §4: 0.4).
  double Alpha = 0.4;
  /// Birth iteration of the initial Gaussians.
  std::int32_t InitialIteration = 0;
  /**
   * Lineage breaks of the log (TrainingLogReader::ReadLineageBreaks; not owned, may be
   * null). Before the event row EventRow[b] (in processing order), a break with Kept = 0
   * ends every Gaussian alive (death at the break, Pruned 0) and each break starts
   * NewRoots roots with the ids FirstNewId.. born at its iteration (GetBreakRoots()).
   */
  const LineageBreakTable* Breaks = nullptr;
};

/**
 * The columns of an event table as read-only arrays of Size values each, so that Build reads
 * events held elsewhere (e.g. a VTK table's arrays) without copying them (at 12M events a copy
 * is 250 MB of fresh memory).
 */
struct EventColumns
{
  const std::int32_t* Iteration = nullptr;
  const std::uint8_t* Kind = nullptr;
  const std::int64_t* Parent = nullptr;
  const std::int64_t* Child = nullptr;
  std::size_t Size = 0;

  /// The columns of @p table; throws std::runtime_error when their lengths differ.
  static EventColumns Of(const EventTable& table);
};

/// One family (a root and its descendants): a row of the family bands table.
struct FamilyBand
{
  std::int64_t RootNode = -1;       ///< node index of the root
  std::int64_t RootGaussianId = -1; ///< GaussianId of the root
  std::int32_t MinIteration = 0;    ///< root birth iteration
  std::int32_t MaxIteration = 0;    ///< largest End (death, or last iteration if alive)
  std::int64_t MinRow = 0;          ///< first layout row (inclusive)
  std::int64_t MaxRow = 0;          ///< last layout row (inclusive)
  std::int64_t NodeCount = 0;       ///< MaxRow - MinRow + 1
  std::int64_t MaxDescendants = 0;  ///< max_F D (= D of the root)
  std::int32_t MaxLifespan = 0;     ///< max_F T
};

/// One step of a root-cause trace (from the selected node up to its root).
struct TraceStep
{
  std::int64_t Node = -1;
  std::int64_t GaussianId = -1;
  std::int32_t BirthIteration = 0;
  std::int32_t DeathIteration = -1;
  BirthKind Kind = BirthKind::Root;
  /// Snapshot iteration used for Value: the snapshot nearest the birth among those in which
  /// the Gaussian exists (Birth <= s and (s < Death or alive)); -1 when it exists in none.
  std::int32_t SnapshotIteration = -1;
  /// Value returned by the callback for (SnapshotIteration, GaussianId); NaN without snapshot.
  double Value = 0.0;
};

/// Per-node input of Genealogy::Assemble (e.g. read back from a vtkTree's vertex arrays).
struct GenealogyNodes
{
  std::vector<std::int64_t> GaussianIds;
  std::vector<std::int64_t> Parents; ///< node index, -1 for roots; Parents[i] < i
  std::vector<std::int32_t> Birth;
  std::vector<std::int32_t> Death; ///< -1 while alive
  std::vector<BirthKind> Kinds;
  std::vector<std::uint8_t> Pruned;
};

/**
 * The genealogy of one training run. Immutable after Build; cheap to move.
 */
class Genealogy
{
public:
  Genealogy() = default;

  /**
   * Builds the tree from the initial ids (the first snapshot's ids, or 0..N0-1), the event
   * table and the last logged iteration (negative: the largest event iteration).
   * Throws std::runtime_error on bad input (see the file comment).
   */
  static Genealogy Build(const std::vector<std::int64_t>& initialIds,
    const EventTable& events,
    std::int32_t lastIteration,
    const GenealogyOptions& options = GenealogyOptions());
  /// Same with initial ids 0..numberOfInitial-1 (DESIGN §3).
  static Genealogy Build(std::int64_t numberOfInitial,
    const EventTable& events,
    std::int32_t lastIteration,
    const GenealogyOptions& options = GenealogyOptions());
  ///@{ The same on event columns held elsewhere (no copy; see EventColumns).
  static Genealogy Build(const std::vector<std::int64_t>& initialIds,
    const EventColumns& events,
    std::int32_t lastIteration,
    const GenealogyOptions& options = GenealogyOptions());
  static Genealogy Build(std::int64_t numberOfInitial,
    const EventColumns& events,
    std::int32_t lastIteration,
    const GenealogyOptions& options = GenealogyOptions());
  ///@}

  /**
   * Rebuilds a genealogy from per-node arrays in creation order (every parent index lower
   * than its child's), recomputing families, D, T, P, rows and bands exactly as Build does.
   * Throws std::runtime_error on inconsistent arrays (sizes, parent order, death before
   * birth, alive after the last iteration, repeated ids).
   */
  static Genealogy Assemble(GenealogyNodes nodes, std::int32_t lastIteration, double alpha = 0.4);

  ///@{ Sizes.
  std::int64_t GetNumberOfNodes() const { return static_cast<std::int64_t>(this->Ids.size()); }
  std::int64_t GetNumberOfFamilies() const { return static_cast<std::int64_t>(this->Bands.size()); }
  std::int32_t GetLastIteration() const { return this->LastIteration; }
  double GetAlpha() const { return this->Alpha; }
  ///@}

  ///@{ Per-node arrays (size N, indexed by node index).
  const std::vector<std::int64_t>& GetGaussianIds() const { return this->Ids; }
  const std::vector<std::int32_t>& GetBirthIterations() const { return this->Birth; }
  /// -1 while alive at the last iteration.
  const std::vector<std::int32_t>& GetDeathIterations() const { return this->Death; }
  const std::vector<BirthKind>& GetBirthKinds() const { return this->Kinds; }
  /// 1 when ended by a prune, else 0.
  const std::vector<std::uint8_t>& GetPruned() const { return this->PrunedFlags; }
  /// Parent node index, -1 for roots.
  const std::vector<std::int64_t>& GetParents() const { return this->Parent; }
  const std::vector<std::int64_t>& GetFamilyIds() const { return this->FamilyOf; }
  const std::vector<std::int64_t>& GetDescendantCounts() const { return this->DescendantCount; }
  const std::vector<std::int32_t>& GetLifespans() const { return this->Lifespan; }
  const std::vector<double>& GetPerceptionValues() const { return this->Perception; }
  /// Layout row (LayoutY); LayoutX is the birth iteration.
  const std::vector<std::int64_t>& GetRows() const { return this->Row; }
  ///@}

  /// Node at layout row @p row (inverse of GetRows()).
  const std::vector<std::int64_t>& GetNodesByRow() const { return this->NodeOfRow; }

  ///@{ Children in CSR form: children of i are Children[ChildOffsets[i] .. ChildOffsets[i+1]).
  const std::vector<std::int64_t>& GetChildOffsets() const { return this->ChildOffsets; }
  const std::vector<std::int64_t>& GetChildren() const { return this->ChildList; }
  std::int64_t GetNumberOfChildren(std::int64_t node) const
  {
    return this->ChildOffsets[node + 1] - this->ChildOffsets[node];
  }
  ///@}

  /// End of the node's life: its death iteration, or the last iteration when alive.
  std::int32_t GetEndIteration(std::int64_t node) const
  {
    return this->Death[node] < 0 ? this->LastIteration : this->Death[node];
  }

  /// Family bands table, indexed by FamilyId.
  const std::vector<FamilyBand>& GetFamilyBands() const { return this->Bands; }

  /// Node index of a GaussianId, or -1 when unknown. O(1).
  std::int64_t FindNode(std::int64_t gaussianId) const;
  /// Node indices of GaussianIds; unknown ids are skipped (counted in @p unknown if given).
  std::vector<std::int64_t> FindNodes(const std::vector<std::int64_t>& gaussianIds,
    std::int64_t* unknown = nullptr) const;

  ///@{
  /**
   * Lineage queries on a selection of node indices (out-of-range indices throw). Results are
   * sorted by node index and free of duplicates. Ancestors/Descendants are *proper* (a
   * selected node is listed only if it is an ancestor/descendant of another selected one);
   * Lineage = selection + ancestors + descendants; Family = every node of the families of
   * the selection. O(k log k + output) time, no per-node allocation, no recursion.
   */
  std::vector<std::int64_t> Ancestors(const std::vector<std::int64_t>& nodes) const;
  std::vector<std::int64_t> Descendants(const std::vector<std::int64_t>& nodes) const;
  std::vector<std::int64_t> Lineage(const std::vector<std::int64_t>& nodes) const;
  std::vector<std::int64_t> Family(const std::vector<std::int64_t>& nodes) const;
  ///@}

  /**
   * Lineage of a selection as sorted, disjoint, non-adjacent-merged inclusive layout-row
   * intervals [first, last] (what the level-of-detail query and the tree view use).
   */
  std::vector<std::pair<std::int64_t, std::int64_t>> LineageRowIntervals(
    const std::vector<std::int64_t>& nodes) const;

  /// Callback of the root-cause trace: value (e.g. View Coverage) of a Gaussian in a snapshot.
  using SnapshotValueFunction =
    std::function<double(std::int32_t snapshotIteration, std::int64_t gaussianId)>;

  /**
   * Root-cause trace: the chain from @p node back to its root (first entry = @p node, last =
   * the root), each with the value the callback returns at the snapshot nearest its birth in
   * which it exists (see TraceStep). @p snapshotIterations need not be sorted. O(depth log S).
   */
  std::vector<TraceStep> TraceToRoot(std::int64_t node,
    const std::vector<std::int32_t>& snapshotIterations,
    const SnapshotValueFunction& value) const;

  ///@{ Diagnostics collected during Build (repairs, reordering).
  const std::vector<std::string>& GetWarnings() const { return this->Warnings; }
  /// Nodes created by RepairUnknownParents.
  const std::vector<std::int64_t>& GetOrphanRoots() const { return this->Orphans; }
  /// Roots started by lineage breaks (GenealogyOptions::Breaks), increasing node indices.
  const std::vector<std::int64_t>& GetBreakRoots() const { return this->BreakRootNodes; }
  /// Event rows (as stored) ignored by RepairDuplicateBirths.
  const std::vector<std::int64_t>& GetDroppedEventRows() const { return this->DroppedRows; }
  /// Whether the events had to be sorted by iteration.
  bool GetEventsWereReordered() const { return this->Reordered; }
  ///@}

  /// One phase of Build: wall-clock and thread-CPU seconds (for benchmarks).
  struct BuildPhase
  {
    std::string Name;
    double WallSeconds = 0.0;
    double CpuSeconds = 0.0;
  };
  /// Phases of the Build that produced this genealogy.
  const std::vector<BuildPhase>& GetBuildPhases() const { return this->Phases; }

  /// Approximate heap memory held, in bytes.
  std::size_t GetMemorySize() const;

private:
  friend class GenealogyBuilder;

  void CheckNode(std::int64_t node) const;

  std::int32_t LastIteration = 0;
  double Alpha = 0.4;

  std::vector<std::int64_t> BreakRootNodes;
  std::vector<std::int64_t> Ids;
  std::vector<std::int32_t> Birth;
  std::vector<std::int32_t> Death;
  std::vector<BirthKind> Kinds;
  std::vector<std::uint8_t> PrunedFlags;
  std::vector<std::int64_t> Parent;
  std::vector<std::int64_t> FamilyOf;
  std::vector<std::int64_t> DescendantCount;
  std::vector<std::int32_t> Lifespan;
  std::vector<double> Perception;
  std::vector<std::int64_t> Row;
  std::vector<std::int64_t> NodeOfRow;
  std::vector<std::int64_t> ChildOffsets;
  std::vector<std::int64_t> ChildList;
  std::vector<FamilyBand> Bands;

  // GaussianId -> node index: identity (node = id - IdMin), dense table (DenseIndex[id -
  // IdMin]) or open-addressing hash.
  bool IdentityIndex = true;
  std::int64_t IdMin = 0;
  std::vector<std::int64_t> DenseIndex;
  std::vector<std::int64_t> HashKeys;
  std::vector<std::int64_t> HashValues;

  std::vector<std::string> Warnings;
  std::vector<std::int64_t> Orphans;
  std::vector<std::int64_t> DroppedRows;
  bool Reordered = false;
  std::vector<BuildPhase> Phases;
};

/// Zoom parameters of DESIGN §4.
struct ZoomParameters
{
  double ZMin = 0.1;
  double ZMax = 2.0;
  double K = 1.2;
};

/**
 * Zoom threshold tau(z) = (1 - (z - zmin)/(zmax - zmin))^k with z clamped to [zmin, zmax]
 * (DESIGN §4). A NaN zoom is treated as zmin (tau = 1, the coarsest level).
 */
double ZoomThreshold(double z, const ZoomParameters& parameters = ZoomParameters());

} // namespace vis4gs

#endif
