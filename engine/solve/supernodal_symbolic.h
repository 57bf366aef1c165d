#pragma once
// Fill-reducing ordering and supernodal symbolic factorisation of a symmetric sparse matrix, run
// on the graph of groups of unknowns rather than on the unknowns: the unknowns of one mesh node
// (two velocity components and a pressure) couple to the same neighbours, so ordering and
// eliminating them together loses nothing, and the graph is about ten times smaller. AMD orders
// the groups (CAMD when some must come last), the elimination tree is postordered, fundamental
// supernodes are relaxed as CHOLMOD relaxes them, and the result is expanded to the unknowns.
#include <array>
#include <span>
#include <vector>

namespace pfem {

struct SupernodalStructure {
  std::vector<int> perm;        // row k of the factor is row perm[k] of the matrix
  std::vector<int> super;       // supernode s holds columns super[s] .. super[s+1]-1
  std::vector<long> pi;         // supernode s's row indices are rows[pi[s]] .. rows[pi[s+1]-1]
  std::vector<long> px;         // its values (rows x columns, column-major) start at px[s]
  std::vector<int> rows;        // per supernode, ascending: its own columns first
  int first_trailing = 0;       // the first supernode holding an unknown of `last` (count if none)
};

// n unknowns in groups: group[k] >= 0 names the group of unknown k (any numbering; empty: each
// unknown its own group, named by its index); the unknowns of a group are given consecutive
// columns, in increasing order, and treated as coupled to each other. couplings: pairs of
// group names that couple (either order; repeats, self pairs and names without unknowns are
// ignored). The groups holding an unknown of `last` are ordered after all others. Throws
// std::invalid_argument on bad groups or unknowns, std::runtime_error if AMD or CAMD fails.
SupernodalStructure supernodal_symbolic(int n, std::span<const int> group,
                                        std::span<const std::array<int, 2>> couplings, std::span<const int> last);

}  // namespace pfem
