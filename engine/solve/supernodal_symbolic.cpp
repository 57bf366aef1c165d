#include "engine/solve/supernodal_symbolic.h"

#include <amd.h>
#include <camd.h>

#include <algorithm>
#include <array>
#include <stdexcept>

namespace pfem {
namespace {

// CHOLMOD's default relaxation: a supernode and its parent merge if the result has at most
// kRelaxColumns[0] columns, or at most kRelaxColumns[i] columns and a fraction of explicit zeros
// below kRelaxZeros[i - 1], or any width and fewer zeros than kRelaxZeros[2].
constexpr int kRelaxColumns[3] = {4, 16, 48};
constexpr double kRelaxZeros[3] = {0.8, 0.1, 0.05};

// Entries of a supernode's lower trapezoid: c columns, r rows (its own columns included).
double trapezoid(long c, long r) { return static_cast<double>(c) * r - 0.5 * static_cast<double>(c) * (c - 1); }

// Lists indexed by a node: the items of node k are item[start[k]] .. item[start[k+1]-1].
struct Lists {
  std::vector<int> start, item;
  int size(int k) const { return start[k + 1] - start[k]; }
  const int* begin(int k) const { return item.data() + start[k]; }
  const int* end(int k) const { return item.data() + start[k + 1]; }
};

// The symmetric graph of the groups (both directions, no self loops, each list sorted and without
// repeats) from coupled pairs of compact group numbers (-1: a group without unknowns, skipped).
Lists group_graph(const std::vector<std::array<int, 2>>& pairs, int ng) {
  std::vector<int> start(ng + 1, 0);
  for (const auto& [a, b] : pairs)
    if (a >= 0 && b >= 0 && a != b) ++start[a + 1], ++start[b + 1];
  for (int k = 0; k < ng; ++k) start[k + 1] += start[k];
  std::vector<int> item(start[ng]), slot(start.begin(), start.end() - 1);
  for (const auto& [a, b] : pairs)
    if (a >= 0 && b >= 0 && a != b) item[slot[a]++] = b, item[slot[b]++] = a;
  Lists graph;
  graph.start.assign(ng + 1, 0);
  graph.item.reserve(item.size() / 2);
  std::vector<int> mark(ng, -1);
  for (int k = 0; k < ng; ++k) {
    for (int p = start[k]; p < start[k + 1]; ++p)
      if (mark[item[p]] != k) mark[item[p]] = k, graph.item.push_back(item[p]);
    graph.start[k + 1] = static_cast<int>(graph.item.size());
    std::sort(graph.item.begin() + graph.start[k], graph.item.end());
  }
  return graph;
}

// The items 0 .. key.size()-1 listed by their key (ascending within each list; key -1: in no
// list): the children of each node of a forest from the parents, the unknowns of each group.
Lists lists_by_key(const std::vector<int>& key, int num_keys) {
  Lists lists;
  lists.start.assign(num_keys + 1, 0);
  for (const int k : key)
    if (k >= 0) ++lists.start[k + 1];
  for (int k = 0; k < num_keys; ++k) lists.start[k + 1] += lists.start[k];
  lists.item.resize(lists.start[num_keys]);
  std::vector<int> slot(lists.start.begin(), lists.start.end() - 1);
  for (int i = 0; i < static_cast<int>(key.size()); ++i)
    if (key[i] >= 0) lists.item[slot[key[i]]++] = i;
  return lists;
}

// A supernode while relaxing: groups first .. last-1, unknown columns and rows (its own
// columns included), explicit zeros.
struct Super {
  int first, last;
  long columns, rows;
  double zeros;
};

}  // namespace

SupernodalStructure supernodal_symbolic(int n, std::span<const int> group,
                                        std::span<const std::array<int, 2>> couplings, std::span<const int> last) {
  if (n < 0 || (!group.empty() && static_cast<int>(group.size()) != n))
    throw std::invalid_argument("supernodal_symbolic: one group per unknown");

  // Groups numbered 0 .. ng-1 in order of first appearance, and their unknowns.
  const auto id_of = [&group](int k) { return group.empty() ? k : group[k]; };
  int max_id = n - 1;
  for (int k = 0; k < n; ++k) {
    if (id_of(k) < 0) throw std::invalid_argument("supernodal_symbolic: a negative group");
    max_id = std::max(max_id, id_of(k));
  }
  std::vector<int> compact(max_id + 1, -1), g(n);
  int ng = 0;
  for (int k = 0; k < n; ++k) {
    int& c = compact[id_of(k)];
    if (c < 0) c = ng++;
    g[k] = c;
  }
  std::vector<std::array<int, 2>> pairs(couplings.size());
  const auto compact_of = [&](int id) { return id >= 0 && id <= max_id ? compact[id] : -1; };
  for (std::size_t q = 0; q < couplings.size(); ++q) pairs[q] = {compact_of(couplings[q][0]), compact_of(couplings[q][1])};
  const Lists members = lists_by_key(g, ng);
  std::vector<int> trailing(ng, 0);
  for (const int k : last) {
    if (k < 0 || k >= n) throw std::invalid_argument("supernodal_symbolic: a last unknown out of range");
    trailing[g[k]] = 1;
  }
  // (CAMD's constraint sets must be numbered below ng: with every group trailing, order freely.)
  const bool constrained = std::find(trailing.begin(), trailing.end(), 1) != trailing.end() &&
                           std::find(trailing.begin(), trailing.end(), 0) != trailing.end();

  // Fill-reducing order of the groups.
  const Lists graph = group_graph(pairs, ng);
  std::vector<int> order(ng);
  if (ng > 0) {
    // AMD refuses a null row-index array, which an empty vector may give (one isolated group).
    const int no_item = 0;
    const int* items = graph.item.empty() ? &no_item : graph.item.data();
    const int status = constrained ? camd_order(ng, graph.start.data(), items, order.data(), nullptr, nullptr,
                                                trailing.data())
                                   : amd_order(ng, graph.start.data(), items, order.data(), nullptr, nullptr);
    if (status < AMD_OK) throw std::runtime_error("the fill-reducing ordering (AMD) failed");
  }
  std::vector<int> position(ng);
  for (int k = 0; k < ng; ++k) position[order[k]] = k;

  // Elimination tree in that order (Liu's algorithm, with path compression).
  std::vector<int> parent(ng, -1), ancestor(ng, -1);
  for (int k = 0; k < ng; ++k)
    for (const int* h = graph.begin(order[k]); h != graph.end(order[k]); ++h) {
      for (int i = position[*h]; i < k;) {
        const int next = ancestor[i];
        ancestor[i] = k;
        if (next < 0) parent[i] = k;
        if (next < 0 || next == k) break;
        i = next;
      }
    }

  // Postorder (each subtree's groups consecutive, so supernodes are), the groups that come last
  // kept after all others and in their order: a topological order of the tree, same fill.
  std::vector<int> post;
  post.reserve(ng);
  {
    std::vector<int> forest(parent);
    for (int k = 0; k < ng; ++k)
      if (trailing[order[k]] || (forest[k] >= 0 && trailing[order[forest[k]]])) forest[k] = -1;
    const Lists children = lists_by_key(forest, ng);
    std::vector<int> next_child(children.start.begin(), children.start.end() - 1), stack;
    for (int root = 0; root < ng; ++root) {
      if (forest[root] >= 0 || trailing[order[root]]) continue;
      stack.push_back(root);
      while (!stack.empty()) {
        const int top = stack.back();
        if (next_child[top] < children.start[top + 1]) {
          stack.push_back(children.item[next_child[top]++]);
        } else {
          stack.pop_back();
          post.push_back(top);
        }
      }
    }
    for (int k = 0; k < ng; ++k)
      if (trailing[order[k]]) post.push_back(k);
  }
  std::vector<int> label(ng), gorder(ng), tree(ng, -1);  // label of each group, group of each label
  for (int m = 0; m < ng; ++m) gorder[m] = order[post[m]], label[order[post[m]]] = m;
  for (int m = 0; m < ng; ++m)
    if (parent[post[m]] >= 0) tree[m] = label[order[parent[post[m]]]];

  // Rows of each group's factor column (labels below the diagonal): its own later neighbours
  // and its children's rows.
  const Lists children = lists_by_key(tree, ng);
  Lists column;
  column.start.assign(ng + 1, 0);
  std::vector<int> mark(ng, -1);
  for (int m = 0; m < ng; ++m) {
    mark[m] = m;
    for (const int* h = graph.begin(gorder[m]); h != graph.end(gorder[m]); ++h)
      if (const int r = label[*h]; r > m && mark[r] != m) mark[r] = m, column.item.push_back(r);
    for (const int* c = children.begin(m); c != children.end(m); ++c)
      for (int q = column.start[*c]; q < column.start[*c + 1]; ++q)  // by index: the list grows
        if (const int r = column.item[q]; mark[r] != m) mark[r] = m, column.item.push_back(r);
    column.start[m + 1] = static_cast<int>(column.item.size());
    std::sort(column.item.begin() + column.start[m], column.item.end());
  }

  // Unknowns per label, then the fundamental supernodes: chains of only children whose columns
  // nest (kept on one side of the trailing boundary).
  std::vector<long> width(ng + 1, 0);  // unknowns before each label
  for (int m = 0; m < ng; ++m) width[m + 1] = width[m] + members.size(gorder[m]);
  const auto below = [&](int m) {  // unknowns in the rows below group column m
    long rows = 0;
    for (const int* r = column.begin(m); r != column.end(m); ++r) rows += width[*r + 1] - width[*r];
    return rows;
  };
  std::vector<Super> fundamental;
  for (int m = 0; m < ng; ++m) {
    const long columns = width[m + 1] - width[m];
    const bool continues = m > 0 && tree[m - 1] == m && children.size(m) == 1 &&
                           column.size(m - 1) == column.size(m) + 1 && trailing[gorder[m - 1]] == trailing[gorder[m]];
    if (continues) {
      Super& f = fundamental.back();
      f.last = m + 1;
      f.columns += columns;
      f.rows = f.columns + below(m);
    } else {
      fundamental.push_back({m, m + 1, columns, columns + below(m), 0.0});
    }
  }
  // Relaxed: a supernode merges into the next one when that holds its parent and the merge adds
  // few explicit zeros.
  std::vector<Super> supers;
  for (const Super& f : fundamental) {
    if (!supers.empty()) {
      Super& c = supers.back();
      const int up = tree[c.last - 1];
      if (up >= f.first && up < f.last && trailing[gorder[c.last - 1]] == trailing[gorder[f.first]]) {
        const long columns = c.columns + f.columns, rows = c.columns + f.rows;
        const double entries = trapezoid(columns, rows);
        const double zeros = entries - (trapezoid(c.columns, c.rows) - c.zeros) - (trapezoid(f.columns, f.rows) - f.zeros);
        const double fraction = zeros / entries;
        if (columns <= kRelaxColumns[0] || (columns <= kRelaxColumns[1] && fraction < kRelaxZeros[0]) ||
            (columns <= kRelaxColumns[2] && fraction < kRelaxZeros[1]) || fraction < kRelaxZeros[2]) {
          c.last = f.last;
          c.columns = columns;
          c.rows = rows;
          c.zeros = zeros;
          continue;
        }
      }
    }
    supers.push_back(f);
  }

  // Expanded to the unknowns.
  SupernodalStructure out;
  out.perm.reserve(n);
  for (int m = 0; m < ng; ++m) out.perm.insert(out.perm.end(), members.begin(gorder[m]), members.end(gorder[m]));
  out.super.push_back(0);
  out.pi.push_back(0);
  out.px.push_back(0);
  out.first_trailing = static_cast<int>(supers.size());
  for (const Super& s : supers) {
    if (trailing[gorder[s.first]] && out.first_trailing == static_cast<int>(supers.size()))
      out.first_trailing = static_cast<int>(out.super.size()) - 1;
    for (long k = width[s.first]; k < width[s.last]; ++k) out.rows.push_back(static_cast<int>(k));
    for (const int* r = column.begin(s.last - 1); r != column.end(s.last - 1); ++r)
      for (long k = width[*r]; k < width[*r + 1]; ++k) out.rows.push_back(static_cast<int>(k));
    out.super.push_back(static_cast<int>(width[s.last]));
    out.pi.push_back(static_cast<long>(out.rows.size()));
    out.px.push_back(out.px.back() + s.columns * (out.pi.back() - out.pi[out.pi.size() - 2]));
  }
  return out;
}

}  // namespace pfem
