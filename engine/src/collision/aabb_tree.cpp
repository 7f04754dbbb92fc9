// Dynamic AABB tree broad phase. Insertion by the surface area heuristic and
// AVL-style rotations follow the published design of Box2D's b2DynamicTree
// (Catto) and Bullet's btDbvt (Presson); the code here is our own.
#include "collision/aabb_tree.h"

#include <algorithm>
#include <cassert>

namespace talus {
namespace {

Aabb Union(const Aabb& a, const Aabb& b) { return {a.min.cwiseMin(b.min), a.max.cwiseMax(b.max)}; }

double SurfaceArea(const Aabb& a) {
  const Vec3 d = a.max - a.min;
  return 2.0 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
}

bool Contains(const Aabb& outer, const Aabb& inner) {
  return (outer.min.array() <= inner.min.array()).all() && (inner.max.array() <= outer.max.array()).all();
}

Aabb Enlarge(const Aabb& box, double radius) {
  const Vec3 margin = Vec3::Constant(kTreeMarginFraction * radius + kTreeMarginAbsolute);
  return {box.min - margin, box.max + margin};
}

}  // namespace

void AabbTree::FindPairs(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                         BroadPhaseStats& stats) {
  out.clear();
  stats.treeReinsertions = Sync(proxies);
  stats.treeHeight = Height();
  std::int64_t candidates = 0;
  SelfPairs(proxies, out, candidates);
  std::sort(out.begin(), out.end());
  stats.candidatePairs = candidates;
  stats.spherePairs = static_cast<std::int64_t>(out.size());
  stats.skippedStaticPairs = 0;
}

int AabbTree::Height() const {
  return m_root == kNull ? 0 : m_nodes[static_cast<std::size_t>(m_root)].height;
}

int AabbTree::Sync(std::span<const BroadPhaseProxy> proxies) {
  int changes = 0;
  // Slots past the end of the array are gone.
  for (std::size_t s = proxies.size(); s < m_leafOfSlot.size(); ++s) {
    if (m_leafOfSlot[s] != kNull) {
      RemoveLeaf(m_leafOfSlot[s]);
      FreeNode(m_leafOfSlot[s]);
      ++changes;
    }
  }
  m_leafOfSlot.resize(proxies.size(), kNull);
  m_exactBox.resize(proxies.size());
  m_slotStatic.resize(proxies.size(), 0);

  for (std::size_t s = 0; s < proxies.size(); ++s) {
    const BroadPhaseProxy& p = proxies[s];
    int& leaf = m_leafOfSlot[s];
    if (!p.active) {
      if (leaf != kNull) {
        RemoveLeaf(leaf);
        FreeNode(leaf);
        leaf = kNull;
        ++changes;
      }
      continue;
    }
    const Aabb exact = ProxyBox(p.sphere);
    m_exactBox[s] = exact;
    const bool flagChanged = (m_slotStatic[s] != 0) != p.isStatic;
    m_slotStatic[s] = p.isStatic ? 1 : 0;
    if (leaf != kNull && !flagChanged && Contains(m_nodes[static_cast<std::size_t>(leaf)].box, exact))
      continue;
    if (leaf != kNull) {
      RemoveLeaf(leaf);
    } else {
      leaf = AllocateNode();
      m_nodes[static_cast<std::size_t>(leaf)].proxy = static_cast<int>(s);
    }
    m_nodes[static_cast<std::size_t>(leaf)].box = Enlarge(exact, p.sphere.radius);
    m_nodes[static_cast<std::size_t>(leaf)].hasDynamic = !p.isStatic;
    InsertLeaf(leaf);
    ++changes;
  }
  return changes;
}

int AabbTree::AllocateNode() {
  if (m_freeList == kNull) {
    m_nodes.push_back(Node{});
    m_freeList = static_cast<int>(m_nodes.size()) - 1;
    m_nodes.back().parent = kNull;
  }
  const int node = m_freeList;
  Node& n = m_nodes[static_cast<std::size_t>(node)];
  m_freeList = n.parent;
  n = Node{};
  return node;
}

void AabbTree::FreeNode(int node) {
  Node& n = m_nodes[static_cast<std::size_t>(node)];
  n.parent = m_freeList;
  n.height = -1;
  n.child1 = n.child2 = n.proxy = kNull;
  m_freeList = node;
}

void AabbTree::InsertLeaf(int leaf) {
  ++m_leafCount;
  if (m_root == kNull) {
    m_root = leaf;
    m_nodes[static_cast<std::size_t>(leaf)].parent = kNull;
    return;
  }
  const Aabb leafBox = m_nodes[static_cast<std::size_t>(leaf)].box;

  // Descend to the sibling that least increases the total surface area: the
  // cost of a new parent here versus the cost of pushing the leaf into a
  // child (that child's growth plus the growth inherited by every ancestor).
  int index = m_root;
  while (!m_nodes[static_cast<std::size_t>(index)].IsLeaf()) {
    const Node& n = m_nodes[static_cast<std::size_t>(index)];
    const double area = SurfaceArea(n.box);
    const double combinedArea = SurfaceArea(Union(n.box, leafBox));
    const double costHere = 2.0 * combinedArea;
    const double inherited = 2.0 * (combinedArea - area);
    auto childCost = [&](int c) {
      const Node& child = m_nodes[static_cast<std::size_t>(c)];
      const double grown = SurfaceArea(Union(child.box, leafBox));
      return (child.IsLeaf() ? grown : grown - SurfaceArea(child.box)) + inherited;
    };
    const double cost1 = childCost(n.child1);
    const double cost2 = childCost(n.child2);
    if (costHere < cost1 && costHere < cost2) break;
    index = cost1 <= cost2 ? n.child1 : n.child2;
  }

  const int sibling = index;
  const int oldParent = m_nodes[static_cast<std::size_t>(sibling)].parent;
  const int newParent = AllocateNode();
  Node& np = m_nodes[static_cast<std::size_t>(newParent)];
  np.parent = oldParent;
  np.box = Union(leafBox, m_nodes[static_cast<std::size_t>(sibling)].box);
  np.height = m_nodes[static_cast<std::size_t>(sibling)].height + 1;
  np.hasDynamic = m_nodes[static_cast<std::size_t>(sibling)].hasDynamic ||
                  m_nodes[static_cast<std::size_t>(leaf)].hasDynamic;
  np.child1 = sibling;
  np.child2 = leaf;
  if (oldParent != kNull) {
    Node& op = m_nodes[static_cast<std::size_t>(oldParent)];
    (op.child1 == sibling ? op.child1 : op.child2) = newParent;
  } else {
    m_root = newParent;
  }
  m_nodes[static_cast<std::size_t>(sibling)].parent = newParent;
  m_nodes[static_cast<std::size_t>(leaf)].parent = newParent;
  RefitUpwards(oldParent);
}

void AabbTree::RemoveLeaf(int leaf) {
  --m_leafCount;
  if (leaf == m_root) {
    m_root = kNull;
    return;
  }
  const int parent = m_nodes[static_cast<std::size_t>(leaf)].parent;
  const Node& p = m_nodes[static_cast<std::size_t>(parent)];
  const int grandParent = p.parent;
  const int sibling = p.child1 == leaf ? p.child2 : p.child1;
  m_nodes[static_cast<std::size_t>(sibling)].parent = grandParent;
  if (grandParent != kNull) {
    Node& g = m_nodes[static_cast<std::size_t>(grandParent)];
    (g.child1 == parent ? g.child1 : g.child2) = sibling;
  } else {
    m_root = sibling;
  }
  FreeNode(parent);
  m_nodes[static_cast<std::size_t>(leaf)].parent = kNull;
  RefitUpwards(grandParent);
}

void AabbTree::RefitUpwards(int node) {
  while (node != kNull) {
    node = Balance(node);
    Node& n = m_nodes[static_cast<std::size_t>(node)];
    const Node& c1 = m_nodes[static_cast<std::size_t>(n.child1)];
    const Node& c2 = m_nodes[static_cast<std::size_t>(n.child2)];
    n.height = 1 + std::max(c1.height, c2.height);
    n.box = Union(c1.box, c2.box);
    n.hasDynamic = c1.hasDynamic || c2.hasDynamic;
    node = n.parent;
  }
}

// Rotation: if one child of A is more than one level taller, that child C
// (children F, G) takes A's place; A keeps its other child and adopts the
// shorter of F and G, C keeps the taller. Heights and boxes of A and C are
// recomputed; everything above is refitted by the caller.
int AabbTree::Balance(int a) {
  Node& na = m_nodes[static_cast<std::size_t>(a)];
  if (na.IsLeaf() || na.height < 2) return a;
  const int h1 = m_nodes[static_cast<std::size_t>(na.child1)].height;
  const int h2 = m_nodes[static_cast<std::size_t>(na.child2)].height;
  if (h1 - h2 >= -1 && h1 - h2 <= 1) return a;

  const bool rotateSecond = h2 > h1;
  const int c = rotateSecond ? na.child2 : na.child1;
  const int other = rotateSecond ? na.child1 : na.child2;
  Node& nc = m_nodes[static_cast<std::size_t>(c)];
  const int f = nc.child1;
  const int g = nc.child2;

  // C replaces A under A's parent.
  nc.parent = na.parent;
  if (nc.parent != kNull) {
    Node& p = m_nodes[static_cast<std::size_t>(nc.parent)];
    (p.child1 == a ? p.child1 : p.child2) = c;
  } else {
    m_root = c;
  }
  na.parent = c;

  const bool fTaller =
      m_nodes[static_cast<std::size_t>(f)].height > m_nodes[static_cast<std::size_t>(g)].height;
  const int keep = fTaller ? f : g;
  const int move = fTaller ? g : f;
  nc.child1 = a;
  nc.child2 = keep;
  (rotateSecond ? na.child2 : na.child1) = move;
  m_nodes[static_cast<std::size_t>(move)].parent = a;

  const Node& no = m_nodes[static_cast<std::size_t>(other)];
  const Node& nm = m_nodes[static_cast<std::size_t>(move)];
  const Node& nk = m_nodes[static_cast<std::size_t>(keep)];
  na.box = Union(no.box, nm.box);
  na.height = 1 + std::max(no.height, nm.height);
  nc.box = Union(na.box, nk.box);
  nc.height = 1 + std::max(na.height, nk.height);
  na.hasDynamic = no.hasDynamic || nm.hasDynamic;
  nc.hasDynamic = na.hasDynamic || nk.hasDynamic;
  return c;
}

// Simultaneous descent of the tree against itself: a node paired with
// itself yields its children's self pairs and their cross pair; two distinct
// nodes whose boxes overlap are split on the taller side until both are
// leaves. Every unordered pair of overlapping leaves is met exactly once.
void AabbTree::SelfPairs(std::span<const BroadPhaseProxy> proxies, std::vector<BroadPhasePair>& out,
                         std::int64_t& candidates) {
  if (m_root == kNull) return;
  m_stack.clear();
  m_stack.push_back({m_root, m_root});
  while (!m_stack.empty()) {
    const auto [x, y] = m_stack.back();
    m_stack.pop_back();
    const Node& nx = m_nodes[static_cast<std::size_t>(x)];
    const Node& ny = m_nodes[static_cast<std::size_t>(y)];
    if (!nx.hasDynamic && !ny.hasDynamic) continue;
    if (x == y) {
      if (nx.IsLeaf()) continue;
      m_stack.push_back({nx.child1, nx.child2});
      m_stack.push_back({nx.child2, nx.child2});
      m_stack.push_back({nx.child1, nx.child1});
      continue;
    }
    if (!BoxesOverlap(nx.box, ny.box)) continue;
    if (nx.IsLeaf() && ny.IsLeaf()) {
      const int a = std::min(nx.proxy, ny.proxy);
      const int b = std::max(nx.proxy, ny.proxy);
      if (!BoxesOverlap(m_exactBox[static_cast<std::size_t>(a)], m_exactBox[static_cast<std::size_t>(b)]))
        continue;
      ++candidates;
      if (SpheresTouch(proxies[static_cast<std::size_t>(a)].sphere,
                       proxies[static_cast<std::size_t>(b)].sphere))
        out.push_back({a, b});
      continue;
    }
    if (ny.IsLeaf() || (!nx.IsLeaf() && nx.height >= ny.height)) {
      m_stack.push_back({nx.child2, y});
      m_stack.push_back({nx.child1, y});
    } else {
      m_stack.push_back({x, ny.child2});
      m_stack.push_back({x, ny.child1});
    }
  }
}

bool AabbTree::IsValid() const {
  int leaves = 0;
  for (std::size_t s = 0; s < m_leafOfSlot.size(); ++s) {
    const int leaf = m_leafOfSlot[s];
    if (leaf == kNull) continue;
    ++leaves;
    const Node& n = m_nodes[static_cast<std::size_t>(leaf)];
    if (!n.IsLeaf() || n.proxy != static_cast<int>(s) || !Contains(n.box, m_exactBox[s])) return false;
    if (n.hasDynamic != (m_slotStatic[s] == 0)) return false;
  }
  if (leaves != m_leafCount) return false;
  if (m_root == kNull) return leaves == 0;
  return IsValidSubtree(m_root, kNull);
}

bool AabbTree::IsValidSubtree(int node, int parent) const {
  const Node& n = m_nodes[static_cast<std::size_t>(node)];
  if (n.parent != parent) return false;
  if (n.IsLeaf()) return n.height == 0 && n.child2 == kNull && n.proxy != kNull;
  const Node& c1 = m_nodes[static_cast<std::size_t>(n.child1)];
  const Node& c2 = m_nodes[static_cast<std::size_t>(n.child2)];
  if (n.proxy != kNull || n.height != 1 + std::max(c1.height, c2.height)) return false;
  if (!Contains(n.box, c1.box) || !Contains(n.box, c2.box)) return false;
  if (n.hasDynamic != (c1.hasDynamic || c2.hasDynamic)) return false;
  return IsValidSubtree(n.child1, node) && IsValidSubtree(n.child2, node);
}

}  // namespace talus
