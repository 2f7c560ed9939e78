// SPDX-License-Identifier: BSD-3-Clause
// Over 1,200 lines on purpose: the one Genealogy class and its builder, which share the
// node arrays' private layout (validation, id index, events, lineage breaks, families, rows,
// bands, lineage queries); the level of detail and the draw index are already their own files.
#include "Genealogy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace vis4gs
{

namespace
{

constexpr std::size_t MaxListedWarnings = 20;

/// CPU time of the calling thread (not inflated by other processes sharing the cores).
double ThreadCpuSeconds()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::uint64_t MixBits(std::uint64_t x)
{
  // splitmix64 finaliser: a good spread for sequential ids.
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

std::string RowText(std::size_t row, std::int32_t iteration, std::uint8_t kind)
{
  std::ostringstream s;
  s << "event row " << row << " (iteration " << iteration << ", " << EventKindName(kind) << ")";
  return s.str();
}

} // namespace

//------------------------------------------------------------------------------
const char* BirthKindName(BirthKind kind)
{
  switch (kind)
  {
    case BirthKind::Root:
      return "root";
    case BirthKind::Clone:
      return "clone";
    case BirthKind::Split:
      return "split";
    case BirthKind::CloneSplit:
      return "clone-split";
  }
  return "unknown";
}

//------------------------------------------------------------------------------
double ZoomThreshold(double z, const ZoomParameters& p)
{
  if (!(p.ZMax > p.ZMin) || !std::isfinite(p.ZMin) || !std::isfinite(p.ZMax) || !(p.K > 0.0) ||
    !std::isfinite(p.K))
  {
    std::ostringstream s;
    s << "ZoomThreshold: invalid parameters zmin=" << p.ZMin << " zmax=" << p.ZMax << " k=" << p.K
      << " (need zmin < zmax and k > 0, all finite)";
    throw std::runtime_error(s.str());
  }
  if (std::isnan(z))
  {
    z = p.ZMin;
  }
  z = std::min(std::max(z, p.ZMin), p.ZMax);
  const double u = (z - p.ZMin) / (p.ZMax - p.ZMin);
  return std::pow(std::max(0.0, 1.0 - u), p.K);
}

//------------------------------------------------------------------------------
/// Builds a Genealogy (friend of Genealogy; see Genealogy.h for the semantics).
class GenealogyBuilder
{
public:
  GenealogyBuilder(Genealogy& g, const EventColumns& events, const GenealogyOptions& options)
    : G(g)
    , Events(events)
    , Options(options)
  {
  }

  void Run(const std::vector<std::int64_t>* initialIds,
    std::int64_t numberOfInitial,
    std::int32_t lastIteration);
  void AssembleFrom(GenealogyNodes& nodes, std::int32_t lastIteration);

private:
  void ValidateRows(std::int32_t& lastIteration);
  void Order();
  void PrepareIndex(const std::vector<std::int64_t>* initialIds, std::int64_t numberOfInitial);
  void IndexInsert(std::int64_t id, std::int64_t node);
  std::int64_t AddNode(std::int64_t id, std::int32_t birth, BirthKind kind, std::int64_t parent);
  void ProcessEvents();
  void ApplyBreaks(std::size_t row);
  template <typename Phase>
  void Finish(Phase& phase);
  void Warn(const std::string& text, std::size_t& counter, const char* summary);
  std::int32_t Bucket(std::int32_t iteration) const
  {
    const std::int32_t interval = this->Options.CoarsenInterval;
    if (interval <= 0)
    {
      return iteration;
    }
    const std::int64_t b =
      (static_cast<std::int64_t>(iteration) + interval - 1) / interval * interval;
    return static_cast<std::int32_t>(std::min<std::int64_t>(b, this->Last));
  }

  Genealogy& G;
  const EventColumns Events;
  GenealogyOptions Options;
  std::int32_t Last = 0;
  std::vector<std::int64_t> Permutation; // processing order (empty: table order)
  std::size_t OrphanWarnings = 0;
  std::size_t DuplicateWarnings = 0;
  std::size_t NextBreak = 0;
  // Coarsened mode: interval of the last clone / split of each node as a parent.
  std::vector<std::int32_t> CloneBucket;
  std::vector<std::int32_t> SplitBucket;
  // Index materialisation (see PrepareIndex).
  std::int64_t DenseLow = 0;
  std::int64_t DenseSpan = 0;
  std::size_t HashCapacity = 16;
};

//------------------------------------------------------------------------------
void GenealogyBuilder::Warn(const std::string& text, std::size_t& counter, const char* summary)
{
  if (counter < MaxListedWarnings)
  {
    this->G.Warnings.push_back(text);
  }
  else if (counter == MaxListedWarnings)
  {
    this->G.Warnings.push_back(summary);
  }
  ++counter;
}

//------------------------------------------------------------------------------
void GenealogyBuilder::ValidateRows(std::int32_t& lastIteration)
{
  const EventColumns& ev = this->Events;
  const std::size_t e = ev.Size;
  if (e > 0 && !(ev.Iteration && ev.Kind && ev.Parent && ev.Child))
  {
    throw std::runtime_error("genealogy: event columns without data");
  }
  if (this->Options.CoarsenInterval < 0)
  {
    throw std::runtime_error("genealogy: CoarsenInterval must be >= 0 (0 = no coarsening)");
  }
  if (!(this->Options.Alpha >= 0.0 && this->Options.Alpha <= 1.0))
  {
    throw std::runtime_error("genealogy: Alpha must lie in [0, 1]");
  }
  std::int32_t maxIteration = this->Options.InitialIteration;
  std::size_t maxRow = 0;
  for (std::size_t r = 0; r < e; ++r)
  {
    const std::int32_t it = ev.Iteration[r];
    const std::uint8_t kind = ev.Kind[r];
    if (it < this->Options.InitialIteration)
    {
      std::ostringstream s;
      s << "genealogy: " << RowText(r, it, kind) << ": iteration is before the initial iteration "
        << this->Options.InitialIteration;
      throw std::runtime_error(s.str());
    }
    if (!IsEventKind(kind))
    {
      std::ostringstream s;
      s << "genealogy: event row " << r << " (iteration " << it << "): unknown kind "
        << static_cast<int>(kind) << " (expected " << EventKindValues << ")";
      throw std::runtime_error(s.str());
    }
    if (ev.Parent[r] < 0)
    {
      std::ostringstream s;
      s << "genealogy: " << RowText(r, it, kind) << ": negative parent GaussianId " << ev.Parent[r];
      throw std::runtime_error(s.str());
    }
    if (kind == 3 && ev.Child[r] != -1)
    {
      std::ostringstream s;
      s << "genealogy: " << RowText(r, it, kind) << ": a prune must have child -1, found "
        << ev.Child[r];
      throw std::runtime_error(s.str());
    }
    if (kind != 3 && ev.Child[r] < 0)
    {
      std::ostringstream s;
      s << "genealogy: " << RowText(r, it, kind) << ": negative child GaussianId " << ev.Child[r];
      throw std::runtime_error(s.str());
    }
    if (it > maxIteration)
    {
      maxIteration = it;
      maxRow = r;
    }
  }
  if (lastIteration < 0)
  {
    lastIteration = maxIteration;
  }
  else if (lastIteration < maxIteration)
  {
    std::ostringstream s;
    s << "genealogy: last iteration " << lastIteration << " is before "
      << RowText(maxRow, maxIteration, ev.Kind[maxRow])
      << " (pass a negative last iteration to use the last event's)";
    throw std::runtime_error(s.str());
  }
  this->Last = lastIteration;
}

//------------------------------------------------------------------------------
void GenealogyBuilder::Order()
{
  const std::int32_t* it = this->Events.Iteration;
  const std::size_t e = this->Events.Size;
  std::size_t firstBad = 0;
  std::size_t badCount = 0;
  for (std::size_t r = 1; r < e; ++r)
  {
    if (it[r] < it[r - 1])
    {
      if (badCount == 0)
      {
        firstBad = r;
      }
      ++badCount;
    }
  }
  if (badCount == 0)
  {
    return;
  }
  std::ostringstream s;
  s << "genealogy: event row " << firstBad << " (iteration " << it[firstBad] << ") comes after row "
    << firstBad - 1 << " (iteration " << it[firstBad - 1] << ")";
  if (this->Options.StrictEventOrder)
  {
    s << ": events must be in non-decreasing iteration order";
    throw std::runtime_error(s.str());
  }
  s << "; " << badCount << " decrease(s) in iteration order: events sorted stably by iteration";
  this->G.Warnings.push_back(s.str());
  this->G.Reordered = true;
  this->Permutation.resize(e);
  std::iota(this->Permutation.begin(), this->Permutation.end(), std::int64_t(0));
  std::stable_sort(this->Permutation.begin(),
    this->Permutation.end(),
    [it](std::int64_t a, std::int64_t b) { return it[a] < it[b]; });
}

//------------------------------------------------------------------------------
void GenealogyBuilder::PrepareIndex(const std::vector<std::int64_t>* initialIds,
  std::int64_t numberOfInitial)
{
  const EventColumns& ev = this->Events;
  std::int64_t lo = std::numeric_limits<std::int64_t>::max();
  std::int64_t hi = std::numeric_limits<std::int64_t>::min();
  if (initialIds)
  {
    for (std::size_t i = 0; i < initialIds->size(); ++i)
    {
      const std::int64_t id = (*initialIds)[i];
      if (id < 0)
      {
        std::ostringstream s;
        s << "genealogy: initial id at position " << i << " is negative (" << id << ")";
        throw std::runtime_error(s.str());
      }
      lo = std::min(lo, id);
      hi = std::max(hi, id);
    }
  }
  else if (numberOfInitial > 0)
  {
    lo = 0;
    hi = numberOfInitial - 1;
  }
  std::int64_t births = 0;
  for (std::size_t r = 0; r < ev.Size; ++r)
  {
    lo = std::min(lo, ev.Parent[r]);
    hi = std::max(hi, ev.Parent[r]);
    if (ev.Kind[r] != 3)
    {
      lo = std::min(lo, ev.Child[r]);
      hi = std::max(hi, ev.Child[r]);
      ++births;
    }
  }
  const LineageBreakTable* breaks = this->Options.Breaks;
  for (std::size_t b = 0; breaks && b < breaks->Size(); ++b)
  {
    if (breaks->NewRoots[b] > 0)
    {
      lo = std::min(lo, breaks->FirstNewId[b]);
      hi = std::max(hi, breaks->FirstNewId[b] + breaks->NewRoots[b] - 1);
      births += breaks->NewRoots[b];
    }
  }
  const std::int64_t initialCount =
    initialIds ? static_cast<std::int64_t>(initialIds->size()) : numberOfInitial;
  // Upper bound on the nodes: initial + births + orphans (at most one per event row).
  const std::int64_t maxNodes = initialCount + births + static_cast<std::int64_t>(ev.Size);
  const std::size_t expected = static_cast<std::size_t>(initialCount + births);
  Genealogy& g = this->G;
  g.Ids.reserve(expected);
  g.Birth.reserve(expected);
  g.Death.reserve(expected);
  g.Kinds.reserve(expected);
  g.PrunedFlags.reserve(expected);
  g.Parent.reserve(expected);
  if (this->Options.CoarsenInterval > 0)
  {
    this->CloneBucket.reserve(expected);
    this->SplitBucket.reserve(expected);
  }
  // The index starts as the identity (node = id - IdMin: ids handed out in creation order,
  // DESIGN §3) and is materialised as a dense table or a hash only when that breaks.
  g.IdentityIndex = true;
  g.IdMin = 0;
  if (hi < lo)
  {
    return; // nothing at all
  }
  const std::uint64_t span = static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo);
  this->DenseSpan = span < static_cast<std::uint64_t>(2 * maxNodes + 1024)
    ? static_cast<std::int64_t>(span + 1)
    : 0;
  this->DenseLow = lo;
  this->HashCapacity = 16;
  while (this->HashCapacity < static_cast<std::size_t>(2 * maxNodes))
  {
    this->HashCapacity *= 2;
  }
}

//------------------------------------------------------------------------------
void GenealogyBuilder::IndexInsert(std::int64_t id, std::int64_t node)
{
  Genealogy& g = this->G;
  if (g.IdentityIndex)
  {
    if (node == 0)
    {
      g.IdMin = id;
      return;
    }
    if (id - g.IdMin == node && id >= g.IdMin)
    {
      return;
    }
    // Materialise the index for the nodes so far.
    g.IdentityIndex = false;
    if (this->DenseSpan > 0)
    {
      g.IdMin = this->DenseLow;
      g.DenseIndex.assign(static_cast<std::size_t>(this->DenseSpan), -1);
    }
    else
    {
      g.HashKeys.assign(this->HashCapacity, -1);
      g.HashValues.assign(this->HashCapacity, -1);
    }
    for (std::int64_t k = 0; k < node; ++k)
    {
      this->IndexInsert(g.Ids[k], k);
    }
  }
  if (!g.DenseIndex.empty())
  {
    g.DenseIndex[static_cast<std::size_t>(id - g.IdMin)] = node;
    return;
  }
  const std::size_t mask = g.HashKeys.size() - 1;
  std::size_t slot = static_cast<std::size_t>(MixBits(static_cast<std::uint64_t>(id))) & mask;
  while (g.HashKeys[slot] != -1 && g.HashKeys[slot] != id)
  {
    slot = (slot + 1) & mask;
  }
  g.HashKeys[slot] = id;
  g.HashValues[slot] = node;
}

//------------------------------------------------------------------------------
std::int64_t GenealogyBuilder::AddNode(std::int64_t id,
  std::int32_t birth,
  BirthKind kind,
  std::int64_t parent)
{
  Genealogy& g = this->G;
  const std::int64_t node = static_cast<std::int64_t>(g.Ids.size());
  g.Ids.push_back(id);
  g.Birth.push_back(birth);
  g.Death.push_back(-1);
  g.Kinds.push_back(kind);
  g.PrunedFlags.push_back(0);
  g.Parent.push_back(parent);
  if (this->Options.CoarsenInterval > 0)
  {
    this->CloneBucket.push_back(-1);
    this->SplitBucket.push_back(-1);
  }
  this->IndexInsert(id, node);
  return node;
}

//------------------------------------------------------------------------------
void GenealogyBuilder::ProcessEvents()
{
  Genealogy& g = this->G;
  const EventColumns& ev = this->Events;
  const std::size_t e = ev.Size;
  const bool coarse = this->Options.CoarsenInterval > 0;
  std::int32_t currentBucket = std::numeric_limits<std::int32_t>::min();
  std::int64_t bucketFirstNode = g.GetNumberOfNodes();

  // Marks the children born in the finished interval whose parent both cloned and split in it.
  auto closeBucket = [&]()
  {
    if (!coarse)
    {
      return;
    }
    const std::int64_t n = g.GetNumberOfNodes();
    for (std::int64_t c = bucketFirstNode; c < n; ++c)
    {
      const std::int64_t p = g.Parent[c];
      if (p >= 0 && this->CloneBucket[p] == currentBucket && this->SplitBucket[p] == currentBucket)
      {
        g.Kinds[c] = BirthKind::CloneSplit;
      }
    }
  };

  for (std::size_t k = 0; k < e; ++k)
  {
    this->ApplyBreaks(k);
    const std::size_t r =
      this->Permutation.empty() ? k : static_cast<std::size_t>(this->Permutation[k]);
    const std::int32_t it = ev.Iteration[r];
    const std::uint8_t kind = ev.Kind[r];
    const std::int64_t parentId = ev.Parent[r];
    const std::int64_t childId = ev.Child[r];
    const std::int32_t when = this->Bucket(it);
    if (when != currentBucket)
    {
      closeBucket();
      currentBucket = when;
      bucketFirstNode = g.GetNumberOfNodes();
    }

    // A Gaussian born twice: the row is rejected before it has any effect.
    if (kind != 3)
    {
      const std::int64_t existing = g.FindNode(childId);
      if (existing >= 0)
      {
        std::ostringstream s;
        s << "genealogy: " << RowText(r, it, kind) << ": child GaussianId " << childId
          << " is born twice (already born at iteration " << g.Birth[existing] << ", "
          << BirthKindName(g.Kinds[existing]) << ")";
        if (!this->Options.RepairDuplicateBirths)
        {
          throw std::runtime_error(s.str());
        }
        g.DroppedRows.push_back(static_cast<std::int64_t>(r));
        this->Warn(s.str() + ": row dropped",
          this->DuplicateWarnings,
          "genealogy: more rows dropped for Gaussians born twice (see GetDroppedEventRows)");
        continue;
      }
    }

    std::int64_t parent = g.FindNode(parentId);
    if (parent < 0)
    {
      std::ostringstream s;
      s << "genealogy: " << RowText(r, it, kind) << ": unknown parent GaussianId " << parentId
        << " (neither an initial Gaussian nor born by an earlier event)";
      if (!this->Options.RepairUnknownParents)
      {
        throw std::runtime_error(s.str());
      }
      parent = this->AddNode(parentId, when, BirthKind::Root, -1);
      g.Orphans.push_back(parent);
      this->Warn(s.str() + ": orphan root created",
        this->OrphanWarnings,
        "genealogy: more orphan roots created (see GetOrphanRoots)");
    }

    const std::int32_t death = g.Death[parent];
    if (death >= 0)
    {
      bool allowed = false;
      if (kind != 3 && !(kind == 2 && g.PrunedFlags[parent]))
      {
        allowed = coarse ? death == when : (kind == 2 && death == when && !g.PrunedFlags[parent]);
      }
      if (!allowed)
      {
        std::ostringstream s;
        s << "genealogy: " << RowText(r, it, kind) << ": GaussianId " << parentId
          << " already ended at iteration " << death << " ("
          << (g.PrunedFlags[parent] ? "pruned" : "split") << ")";
        throw std::runtime_error(s.str());
      }
    }

    switch (kind)
    {
      case 1:
        this->AddNode(childId, when, BirthKind::Clone, parent);
        if (coarse)
        {
          this->CloneBucket[parent] = when;
        }
        break;
      case 2:
        this->AddNode(childId, when, BirthKind::Split, parent);
        g.Death[parent] = when;
        if (coarse)
        {
          this->SplitBucket[parent] = when;
        }
        break;
      default:
        g.Death[parent] = when;
        g.PrunedFlags[parent] = 1;
        break;
    }
  }
  closeBucket();
  this->ApplyBreaks(std::numeric_limits<std::size_t>::max());
}

//------------------------------------------------------------------------------
void GenealogyBuilder::ApplyBreaks(std::size_t row)
{
  const LineageBreakTable* breaks = this->Options.Breaks;
  Genealogy& g = this->G;
  for (; breaks && this->NextBreak < breaks->Size() &&
       static_cast<std::size_t>(breaks->EventRow[this->NextBreak]) <= row;
       ++this->NextBreak)
  {
    const std::size_t b = this->NextBreak;
    const std::int32_t when = this->Bucket(std::min(breaks->Iteration[b], this->Last));
    if (breaks->Kept[b] == 0)
    {
      for (std::int32_t& death : g.Death)
      {
        death = death < 0 ? when : death;
      }
    }
    for (std::int64_t k = 0; k < breaks->NewRoots[b]; ++k)
    {
      const std::int64_t id = breaks->FirstNewId[b] + k;
      if (g.FindNode(id) >= 0)
      {
        std::ostringstream s;
        s << "genealogy: lineage break " << b << " (iteration " << breaks->Iteration[b]
          << ") starts a new root with GaussianId " << id << ", which already exists";
        throw std::runtime_error(s.str());
      }
      g.BreakRootNodes.push_back(this->AddNode(id, when, BirthKind::Root, -1));
    }
  }
}

//------------------------------------------------------------------------------
template <typename Phase>
void GenealogyBuilder::Finish(Phase& phase)
{
  Genealogy& g = this->G;
  const std::int64_t n = g.GetNumberOfNodes();
  const std::size_t un = static_cast<std::size_t>(n);
  g.LastIteration = this->Last;
  g.Alpha = this->Options.Alpha;
  this->CloneBucket = std::vector<std::int32_t>();
  this->SplitBucket = std::vector<std::int32_t>();

  // Children (CSR, creation order because node indices follow creation order).
  g.ChildOffsets.assign(un + 1, 0);
  for (std::int64_t i = 0; i < n; ++i)
  {
    if (g.Parent[i] >= 0)
    {
      ++g.ChildOffsets[g.Parent[i] + 1];
    }
  }
  for (std::size_t i = 0; i < un; ++i)
  {
    g.ChildOffsets[i + 1] += g.ChildOffsets[i];
  }
  g.ChildList.resize(static_cast<std::size_t>(g.ChildOffsets[un]));
  // Fill with ChildOffsets[p] (the start of node p's list) as node p's cursor: it ends at the
  // start of node p + 1's list; then shift the offsets up by one. No separate cursor array.
  for (std::int64_t i = 0; i < n; ++i)
  {
    if (g.Parent[i] >= 0)
    {
      g.ChildList[g.ChildOffsets[g.Parent[i]]++] = i;
    }
  }
  for (std::size_t i = un; i > 0; --i)
  {
    g.ChildOffsets[i] = g.ChildOffsets[i - 1];
  }
  g.ChildOffsets[0] = 0;

  phase("children CSR");
  // Families (parents precede children).
  g.FamilyOf.resize(un);
  std::int64_t families = 0;
  for (std::int64_t i = 0; i < n; ++i)
  {
    g.FamilyOf[i] = g.Parent[i] < 0 ? families++ : g.FamilyOf[g.Parent[i]];
  }

  phase("families");
  // Descendant counts (children follow parents: one reverse pass).
  g.DescendantCount.assign(un, 0);
  for (std::int64_t i = n - 1; i >= 0; --i)
  {
    if (g.Parent[i] >= 0)
    {
      g.DescendantCount[g.Parent[i]] += g.DescendantCount[i] + 1;
    }
  }

  phase("descendant counts");
  // Lifespans and family bands.
  g.Lifespan.resize(un);
  {
    const std::int32_t last = this->Last;
    const std::int32_t* death = g.Death.data();
    const std::int32_t* birth = g.Birth.data();
    std::int32_t* lifespan = g.Lifespan.data();
#pragma omp parallel for schedule(static) if (n > 65536)
    for (std::int64_t i = 0; i < n; ++i)
    {
      lifespan[i] = (death[i] < 0 ? last : death[i]) - birth[i];
    }
  }
  g.Bands.assign(static_cast<std::size_t>(families), FamilyBand());
  std::int64_t nextRow = 0;
  for (std::int64_t i = 0; i < n; ++i)
  {
    const std::int32_t end = g.Death[i] < 0 ? this->Last : g.Death[i];
    FamilyBand& band = g.Bands[g.FamilyOf[i]];
    if (g.Parent[i] < 0)
    {
      band.RootNode = i;
      band.RootGaussianId = g.Ids[i];
      band.MinIteration = g.Birth[i];
      band.MaxIteration = end;
      band.NodeCount = g.DescendantCount[i] + 1;
      band.MinRow = nextRow;
      band.MaxRow = nextRow + band.NodeCount - 1;
      band.MaxDescendants = g.DescendantCount[i];
      band.MaxLifespan = g.Lifespan[i];
      nextRow += band.NodeCount;
    }
    else
    {
      band.MaxIteration = std::max(band.MaxIteration, end);
      band.MaxLifespan = std::max(band.MaxLifespan, g.Lifespan[i]);
    }
  }

  phase("lifespans and bands");
  // Perception values (DESIGN §4).
  g.Perception.resize(un);
  const double alpha = this->Options.Alpha;
#pragma omp parallel for schedule(static) if (n > 65536)
  for (std::int64_t i = 0; i < n; ++i)
  {
    const FamilyBand& band = g.Bands[g.FamilyOf[i]];
    double p = 0.0;
    if (band.MaxDescendants > 0)
    {
      p += alpha * static_cast<double>(g.DescendantCount[i]) /
        static_cast<double>(band.MaxDescendants);
    }
    if (band.MaxLifespan > 0)
    {
      p +=
        (1.0 - alpha) * static_cast<double>(g.Lifespan[i]) / static_cast<double>(band.MaxLifespan);
    }
    g.Perception[i] = p;
  }

  phase("perception values");
  // Rows: pre-order with children in creation order, without a stack: a child's row is its
  // parent's row + 1 + the sizes of its earlier-born siblings' subtrees.
  // First each child's offset below its parent's row (independent per parent: parallel),
  // then the rows in node order (parents precede children).
  g.Row.resize(un);
  {
    std::int64_t* row = g.Row.data();
    const std::int64_t* offsets = g.ChildOffsets.data();
    const std::int64_t* children = g.ChildList.data();
    const std::int64_t* descendants = g.DescendantCount.data();
#pragma omp parallel for schedule(dynamic, 16384) if (n > 65536)
    for (std::int64_t i = 0; i < n; ++i)
    {
      std::int64_t next = 1;
      for (std::int64_t k = offsets[i]; k < offsets[i + 1]; ++k)
      {
        const std::int64_t c = children[k];
        row[c] = next;
        next += descendants[c] + 1;
      }
    }
  }
  for (std::int64_t i = 0; i < n; ++i)
  {
    g.Row[i] = g.Parent[i] < 0 ? g.Bands[g.FamilyOf[i]].MinRow : g.Row[g.Parent[i]] + g.Row[i];
  }
  g.NodeOfRow.resize(un);
  {
    // Rows are a permutation of 0..n-1: the threads write distinct entries.
    const std::int64_t* row = g.Row.data();
    std::int64_t* nodeOfRow = g.NodeOfRow.data();
#pragma omp parallel for schedule(static) if (n > 65536)
    for (std::int64_t i = 0; i < n; ++i)
    {
      nodeOfRow[row[i]] = i;
    }
  }
  phase("layout rows");
}

//------------------------------------------------------------------------------
void GenealogyBuilder::Run(const std::vector<std::int64_t>* initialIds,
  std::int64_t numberOfInitial,
  std::int32_t lastIteration)
{
  if (!initialIds && numberOfInitial < 0)
  {
    throw std::runtime_error("genealogy: negative number of initial Gaussians");
  }
  auto tick = std::chrono::steady_clock::now();
  double cpuTick = ThreadCpuSeconds();
  auto phase = [&](const char* name)
  {
    const auto now = std::chrono::steady_clock::now();
    const double cpu = ThreadCpuSeconds();
    Genealogy::BuildPhase p;
    p.Name = name;
    p.WallSeconds = std::chrono::duration<double>(now - tick).count();
    p.CpuSeconds = cpu - cpuTick;
    this->G.Phases.push_back(p);
    tick = now;
    cpuTick = cpu;
  };
  this->ValidateRows(lastIteration);
  this->Order();
  phase("validate and order events");
  this->PrepareIndex(initialIds, numberOfInitial);
  const std::int32_t rootBirth = this->Options.InitialIteration;
  if (initialIds)
  {
    std::size_t duplicates = 0;
    for (std::size_t i = 0; i < initialIds->size(); ++i)
    {
      const std::int64_t id = (*initialIds)[i];
      const std::int64_t existing = this->G.FindNode(id);
      if (existing >= 0)
      {
        std::ostringstream s;
        s << "genealogy: initial ids: GaussianId " << id << " appears twice (positions " << existing
          << " and " << i << ")";
        if (!this->Options.RepairDuplicateBirths)
        {
          throw std::runtime_error(s.str());
        }
        this->Warn(
          s.str() + ": kept once", duplicates, "genealogy: more repeated initial ids kept once");
        continue;
      }
      this->AddNode(id, rootBirth, BirthKind::Root, -1);
    }
  }
  else
  {
    for (std::int64_t id = 0; id < numberOfInitial; ++id)
    {
      this->AddNode(id, rootBirth, BirthKind::Root, -1);
    }
  }
  phase("initial nodes and id index");
  this->ProcessEvents();
  phase("process events");
  this->Finish(phase);
}

//------------------------------------------------------------------------------
EventColumns EventColumns::Of(const EventTable& t)
{
  const std::size_t e = t.Iteration.size();
  if (t.Kind.size() != e || t.Parent.size() != e || t.Child.size() != e)
  {
    std::ostringstream s;
    s << "genealogy: event table columns have different lengths (iteration " << e << ", kind "
      << t.Kind.size() << ", parent " << t.Parent.size() << ", child " << t.Child.size() << ")";
    throw std::runtime_error(s.str());
  }
  EventColumns c;
  c.Iteration = t.Iteration.data();
  c.Kind = t.Kind.data();
  c.Parent = t.Parent.data();
  c.Child = t.Child.data();
  c.Size = e;
  return c;
}

//------------------------------------------------------------------------------
Genealogy Genealogy::Build(const std::vector<std::int64_t>& initialIds,
  const EventTable& events,
  std::int32_t lastIteration,
  const GenealogyOptions& options)
{
  return Build(initialIds, EventColumns::Of(events), lastIteration, options);
}

//------------------------------------------------------------------------------
Genealogy Genealogy::Build(std::int64_t numberOfInitial,
  const EventTable& events,
  std::int32_t lastIteration,
  const GenealogyOptions& options)
{
  return Build(numberOfInitial, EventColumns::Of(events), lastIteration, options);
}

//------------------------------------------------------------------------------
Genealogy Genealogy::Build(const std::vector<std::int64_t>& initialIds,
  const EventColumns& events,
  std::int32_t lastIteration,
  const GenealogyOptions& options)
{
  Genealogy g;
  GenealogyBuilder(g, events, options).Run(&initialIds, 0, lastIteration);
  return g;
}

//------------------------------------------------------------------------------
Genealogy Genealogy::Build(std::int64_t numberOfInitial,
  const EventColumns& events,
  std::int32_t lastIteration,
  const GenealogyOptions& options)
{
  Genealogy g;
  GenealogyBuilder(g, events, options).Run(nullptr, numberOfInitial, lastIteration);
  return g;
}

//------------------------------------------------------------------------------
void GenealogyBuilder::AssembleFrom(GenealogyNodes& nodes, std::int32_t lastIteration)
{
  Genealogy& g = this->G;
  const std::size_t n = nodes.GaussianIds.size();
  if (nodes.Parents.size() != n || nodes.Birth.size() != n || nodes.Death.size() != n ||
    nodes.Kinds.size() != n || nodes.Pruned.size() != n)
  {
    throw std::runtime_error("genealogy: node arrays have different lengths");
  }
  std::int64_t lo = std::numeric_limits<std::int64_t>::max();
  std::int64_t hi = std::numeric_limits<std::int64_t>::min();
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::int64_t p = nodes.Parents[i];
    std::ostringstream s;
    if (nodes.GaussianIds[i] < 0)
    {
      s << "genealogy: node " << i << " has a negative GaussianId";
    }
    else if (p < -1 || p >= static_cast<std::int64_t>(i))
    {
      s << "genealogy: node " << i << " has parent " << p
        << " (parents must precede their children)";
    }
    else if (nodes.Death[i] >= 0 && nodes.Death[i] < nodes.Birth[i])
    {
      s << "genealogy: node " << i << " dies at " << nodes.Death[i] << " before its birth at "
        << nodes.Birth[i];
    }
    else if (nodes.Death[i] < 0 && nodes.Birth[i] > lastIteration)
    {
      s << "genealogy: node " << i << " is born at " << nodes.Birth[i]
        << " after the last iteration " << lastIteration;
    }
    else if (nodes.Death[i] > lastIteration)
    {
      s << "genealogy: node " << i << " dies at " << nodes.Death[i] << " after the last iteration "
        << lastIteration;
    }
    if (!s.str().empty())
    {
      throw std::runtime_error(s.str());
    }
    lo = std::min(lo, nodes.GaussianIds[i]);
    hi = std::max(hi, nodes.GaussianIds[i]);
  }
  this->Last = lastIteration;
  if (n > 0)
  {
    const std::uint64_t span = static_cast<std::uint64_t>(hi) - static_cast<std::uint64_t>(lo);
    this->DenseSpan = span < 2 * n + 1024 ? static_cast<std::int64_t>(span + 1) : 0;
    this->DenseLow = lo;
    while (this->HashCapacity < 2 * n)
    {
      this->HashCapacity *= 2;
    }
  }
  g.IdentityIndex = true;
  g.Ids.clear();
  g.Ids.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::int64_t id = nodes.GaussianIds[i];
    const std::int64_t existing = g.FindNode(id);
    if (existing >= 0)
    {
      std::ostringstream s;
      s << "genealogy: GaussianId " << id << " appears twice (nodes " << existing << " and " << i
        << ")";
      throw std::runtime_error(s.str());
    }
    g.Ids.push_back(id);
    this->IndexInsert(id, static_cast<std::int64_t>(i));
  }
  g.Parent = std::move(nodes.Parents);
  g.Birth = std::move(nodes.Birth);
  g.Death = std::move(nodes.Death);
  g.Kinds = std::move(nodes.Kinds);
  g.PrunedFlags = std::move(nodes.Pruned);
  auto noPhase = [](const char*) {};
  this->Finish(noPhase);
}

//------------------------------------------------------------------------------
Genealogy Genealogy::Assemble(GenealogyNodes nodes, std::int32_t lastIteration, double alpha)
{
  Genealogy g;
  GenealogyOptions options;
  options.Alpha = alpha;
  if (!(alpha >= 0.0 && alpha <= 1.0))
  {
    throw std::runtime_error("genealogy: Alpha must lie in [0, 1]");
  }
  GenealogyBuilder(g, EventColumns(), options).AssembleFrom(nodes, lastIteration);
  return g;
}

//------------------------------------------------------------------------------
std::int64_t Genealogy::FindNode(std::int64_t id) const
{
  if (this->IdentityIndex)
  {
    return id >= this->IdMin && id - this->IdMin < this->GetNumberOfNodes() ? id - this->IdMin : -1;
  }
  if (!this->DenseIndex.empty())
  {
    if (id < this->IdMin)
    {
      return -1;
    }
    const std::uint64_t k = static_cast<std::uint64_t>(id - this->IdMin);
    return k < this->DenseIndex.size() ? this->DenseIndex[static_cast<std::size_t>(k)] : -1;
  }
  if (this->HashKeys.empty() || id < 0)
  {
    return -1;
  }
  const std::size_t mask = this->HashKeys.size() - 1;
  std::size_t slot = static_cast<std::size_t>(MixBits(static_cast<std::uint64_t>(id))) & mask;
  while (this->HashKeys[slot] != -1)
  {
    if (this->HashKeys[slot] == id)
    {
      return this->HashValues[slot];
    }
    slot = (slot + 1) & mask;
  }
  return -1;
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> Genealogy::FindNodes(const std::vector<std::int64_t>& gaussianIds,
  std::int64_t* unknown) const
{
  std::vector<std::int64_t> out;
  out.reserve(gaussianIds.size());
  std::int64_t missing = 0;
  for (std::int64_t id : gaussianIds)
  {
    const std::int64_t node = this->FindNode(id);
    if (node >= 0)
    {
      out.push_back(node);
    }
    else
    {
      ++missing;
    }
  }
  if (unknown)
  {
    *unknown = missing;
  }
  return out;
}

//------------------------------------------------------------------------------
void Genealogy::CheckNode(std::int64_t node) const
{
  if (node < 0 || node >= this->GetNumberOfNodes())
  {
    std::ostringstream s;
    s << "genealogy: node index " << node << " out of range [0, " << this->GetNumberOfNodes()
      << ")";
    throw std::runtime_error(s.str());
  }
}

namespace
{
/// Selected nodes, checked, unique, sorted by row.
std::vector<std::int64_t> SortedByRow(const Genealogy& g, const std::vector<std::int64_t>& nodes)
{
  std::vector<std::int64_t> rows;
  rows.reserve(nodes.size());
  for (std::int64_t v : nodes)
  {
    if (v < 0 || v >= g.GetNumberOfNodes())
    {
      std::ostringstream s;
      s << "genealogy: node index " << v << " out of range [0, " << g.GetNumberOfNodes() << ")";
      throw std::runtime_error(s.str());
    }
    rows.push_back(g.GetRows()[v]);
  }
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  for (std::int64_t& r : rows)
  {
    r = g.GetNodesByRow()[r];
  }
  return rows;
}

void AppendRows(const Genealogy& g,
  const std::vector<std::pair<std::int64_t, std::int64_t>>& iv,
  std::vector<std::int64_t>& out)
{
  const std::vector<std::int64_t>& byRow = g.GetNodesByRow();
  for (const auto& r : iv)
  {
    out.insert(out.end(), byRow.begin() + r.first, byRow.begin() + r.second + 1);
  }
}

void MergeIntervals(std::vector<std::pair<std::int64_t, std::int64_t>>& iv)
{
  std::sort(iv.begin(), iv.end());
  std::size_t w = 0;
  for (std::size_t i = 0; i < iv.size(); ++i)
  {
    if (w > 0 && iv[i].first <= iv[w - 1].second + 1)
    {
      iv[w - 1].second = std::max(iv[w - 1].second, iv[i].second);
    }
    else
    {
      iv[w++] = iv[i];
    }
  }
  iv.resize(w);
}
} // namespace

//------------------------------------------------------------------------------
std::vector<std::int64_t> Genealogy::Ancestors(const std::vector<std::int64_t>& nodes) const
{
  const std::vector<std::int64_t> sel = SortedByRow(*this, nodes);
  std::vector<std::int64_t> out;
  // Processing in row order: an ancestor u of v with row(u) < row(previous selected) is an
  // ancestor of that previous node, so its chain was already listed. Each node is listed once.
  std::int64_t previousRow = -1;
  for (std::int64_t v : sel)
  {
    std::int64_t u = this->Parent[v];
    while (u >= 0 && this->Row[u] >= previousRow)
    {
      out.push_back(u);
      if (this->Row[u] == previousRow)
      {
        break;
      }
      u = this->Parent[u];
    }
    previousRow = this->Row[v];
  }
  std::sort(out.begin(), out.end());
  return out;
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> Genealogy::Descendants(const std::vector<std::int64_t>& nodes) const
{
  const std::vector<std::int64_t> sel = SortedByRow(*this, nodes);
  std::vector<std::pair<std::int64_t, std::int64_t>> iv;
  for (std::int64_t v : sel)
  {
    if (this->DescendantCount[v] > 0)
    {
      iv.emplace_back(this->Row[v] + 1, this->Row[v] + this->DescendantCount[v]);
    }
  }
  MergeIntervals(iv);
  std::vector<std::int64_t> out;
  AppendRows(*this, iv, out);
  std::sort(out.begin(), out.end());
  return out;
}

//------------------------------------------------------------------------------
std::vector<std::pair<std::int64_t, std::int64_t>> Genealogy::LineageRowIntervals(
  const std::vector<std::int64_t>& nodes) const
{
  std::vector<std::pair<std::int64_t, std::int64_t>> iv;
  for (std::int64_t a : this->Ancestors(nodes))
  {
    iv.emplace_back(this->Row[a], this->Row[a]);
  }
  for (std::int64_t v : nodes)
  {
    iv.emplace_back(this->Row[v], this->Row[v] + this->DescendantCount[v]);
  }
  MergeIntervals(iv);
  return iv;
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> Genealogy::Lineage(const std::vector<std::int64_t>& nodes) const
{
  std::vector<std::int64_t> out;
  AppendRows(*this, this->LineageRowIntervals(nodes), out);
  std::sort(out.begin(), out.end());
  return out;
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> Genealogy::Family(const std::vector<std::int64_t>& nodes) const
{
  std::vector<std::pair<std::int64_t, std::int64_t>> iv;
  for (std::int64_t v : nodes)
  {
    this->CheckNode(v);
    const FamilyBand& band = this->Bands[this->FamilyOf[v]];
    iv.emplace_back(band.MinRow, band.MaxRow);
  }
  MergeIntervals(iv);
  std::vector<std::int64_t> out;
  AppendRows(*this, iv, out);
  std::sort(out.begin(), out.end());
  return out;
}

//------------------------------------------------------------------------------
std::vector<TraceStep> Genealogy::TraceToRoot(std::int64_t node,
  const std::vector<std::int32_t>& snapshotIterations,
  const SnapshotValueFunction& value) const
{
  this->CheckNode(node);
  std::vector<std::int32_t> snaps(snapshotIterations);
  std::sort(snaps.begin(), snaps.end());
  snaps.erase(std::unique(snaps.begin(), snaps.end()), snaps.end());
  std::vector<TraceStep> out;
  for (std::int64_t u = node; u >= 0; u = this->Parent[u])
  {
    TraceStep step;
    step.Node = u;
    step.GaussianId = this->Ids[u];
    step.BirthIteration = this->Birth[u];
    step.DeathIteration = this->Death[u];
    step.Kind = this->Kinds[u];
    step.Value = std::numeric_limits<double>::quiet_NaN();
    // Nearest snapshot to the birth among those the Gaussian exists in: all such snapshots
    // are >= birth, so it is the first one >= birth, if the Gaussian still exists there.
    const auto s = std::lower_bound(snaps.begin(), snaps.end(), this->Birth[u]);
    if (s != snaps.end() && (this->Death[u] < 0 || *s < this->Death[u]))
    {
      step.SnapshotIteration = *s;
      if (value)
      {
        step.Value = value(*s, this->Ids[u]);
      }
    }
    out.push_back(step);
  }
  return out;
}

//------------------------------------------------------------------------------
std::size_t Genealogy::GetMemorySize() const
{
  auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return bytes(this->Ids) + bytes(this->Birth) + bytes(this->Death) + bytes(this->Kinds) +
    bytes(this->PrunedFlags) + bytes(this->Parent) + bytes(this->FamilyOf) +
    bytes(this->DescendantCount) + bytes(this->Lifespan) + bytes(this->Perception) +
    bytes(this->Row) + bytes(this->NodeOfRow) + bytes(this->ChildOffsets) + bytes(this->ChildList) +
    this->Bands.capacity() * sizeof(FamilyBand) + bytes(this->DenseIndex) + bytes(this->HashKeys) +
    bytes(this->HashValues);
}

} // namespace vis4gs
