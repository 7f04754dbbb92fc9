// Dynamic AABB tree broad phase. Insertion by the surface area heuristic and
// rotations by surface area follow the published design of Box2D's dynamic
// tree (Catto) and Bullet's btDbvt (Presson); the code here is our own.
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

void AabbTree::Refit(int node) {
  Node& n = m_nodes[static_cast<std::size_t>(node)];
  const Node& c1 = m_nodes[static_cast<std::size_t>(n.child1)];
  const Node& c2 = m_nodes[static_cast<std::size_t>(n.child2)];
  n.height = 1 + std::max(c1.height, c2.height);
  n.box = Union(c1.box, c2.box);
  n.hasDynamic = c1.hasDynamic || c2.hasDynamic;
}

void AabbTree::RefitUpwards(int node) {
  while (node != kNull) {
    Refit(node);
    Rotate(node);
    node = m_nodes[static_cast<std::size_t>(node)].parent;
  }
}

// Tree rotation by surface area (the idea of Box2D v3's b2RotateNodes, after
// Kopta et al., "Fast, effective BVH updates for animated scenes"): at node A
// with children B and C, swapping B with a child of C (or C with a child of
// B) keeps A's box but can shrink the box of the child that changes. Take
// the swap that shrinks it most, if any. Rotations by height alone (as in
// Box2D v2.4) keep the tree shallow but let boxes grow loose: measured 254
// node visits per body at 100k bodies, against 53 without any rotation.
void AabbTree::Rotate(int a) {
  const Node& na = m_nodes[static_cast<std::size_t>(a)];
  if (na.IsLeaf()) return;
  const int b = na.child1;
  const int c = na.child2;
  double bestGain = 0.0;
  int moveUp = kNull;    // grandchild that moves up to be A's child
  int moveDown = kNull;  // A's child that moves down in its place
  // Swapping `down` (a child of A) with grandchild `up` under `parent`,
  // whose other child is `stay`: parent's box becomes down + stay.
  auto consider = [&](int down, int parent, int up, int stay) {
    const double before = SurfaceArea(m_nodes[static_cast<std::size_t>(parent)].box);
    const double after = SurfaceArea(
        Union(m_nodes[static_cast<std::size_t>(down)].box, m_nodes[static_cast<std::size_t>(stay)].box));
    if (before - after > bestGain) {
      bestGain = before - after;
      moveUp = up;
      moveDown = down;
    }
  };
  const Node& nb = m_nodes[static_cast<std::size_t>(b)];
  const Node& nc = m_nodes[static_cast<std::size_t>(c)];
  if (!nc.IsLeaf()) {
    consider(b, c, nc.child1, nc.child2);
    consider(b, c, nc.child2, nc.child1);
  }
  if (!nb.IsLeaf()) {
    consider(c, b, nb.child1, nb.child2);
    consider(c, b, nb.child2, nb.child1);
  }
  if (moveUp == kNull) return;

  const int parent = m_nodes[static_cast<std::size_t>(moveUp)].parent;
  Node& np = m_nodes[static_cast<std::size_t>(parent)];
  (np.child1 == moveUp ? np.child1 : np.child2) = moveDown;
  m_nodes[static_cast<std::size_t>(moveDown)].parent = parent;
  Node& nodeA = m_nodes[static_cast<std::size_t>(a)];
  (nodeA.child1 == moveDown ? nodeA.child1 : nodeA.child2) = moveUp;
  m_nodes[static_cast<std::size_t>(moveUp)].parent = a;
  Refit(parent);
  Refit(a);
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
