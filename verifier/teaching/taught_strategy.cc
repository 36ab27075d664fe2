// Taught strategies as trees (taught_strategy.h).
#include "verifier/teaching/taught_strategy.h"

#include <sstream>
#include <stdexcept>

namespace cmt::teaching {
namespace {

// Copies the subtree of `from` rooted at `node` into `out` in pre-order (the loader's node order: a node, the
// rest of its list, then its branches' lists) under `parent` and its branch `branch`; returns the copy's id.
int copy_subtree(const Strategy& from, int node, Strategy& out, int parent, int branch) {
  const StrategyNode& source = from.nodes.at(static_cast<std::size_t>(node));
  const int id = static_cast<int>(out.nodes.size());
  StrategyNode copy;
  copy.motion = source.motion;
  copy.parent = parent;
  copy.branch = branch;
  copy.branches = source.branches;
  out.nodes.push_back(copy);
  out.motions.push_back(source.motion);
  if (source.next >= 0) {
    const int next = copy_subtree(from, source.next, out, id, -1);
    out.nodes[static_cast<std::size_t>(id)].next = next;
  }
  for (std::size_t b = 0; b < source.branches.size(); ++b) {
    const int first = source.branches[b].first;
    const int copied = first < 0 ? -1 : copy_subtree(from, first, out, id, static_cast<int>(b));
    out.nodes[static_cast<std::size_t>(id)].branches[b].first = copied;
  }
  return id;
}

bool same_termination(const MotionTermination& a, const MotionTermination& b) {
  if (a.position.size() != b.position.size() || a.force.size() != b.force.size()) return false;
  for (std::size_t i = 0; i < a.position.size(); ++i)
    if (a.position[i].min != b.position[i].min || a.position[i].max != b.position[i].max) return false;
  for (std::size_t i = 0; i < a.force.size(); ++i)
    if (a.force[i].direction != b.force[i].direction || a.force[i].angle != b.force[i].angle) return false;
  return true;
}

// "position in 1 box", "position in 2 boxes and force in 1 cone".
std::string test_text(const MotionTermination& when) {
  const auto count = [](std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + (n == 1 ? one : many);
  };
  std::string out;
  if (!when.position.empty()) out = "position in " + count(when.position.size(), " box", " boxes");
  if (!when.force.empty())
    out +=
        (out.empty() ? "" : " and ") + std::string("force in ") + count(when.force.size(), " cone", " cones");
  return out;
}

void write_list(const Strategy& s, int node, std::ostream& os) {
  for (bool first = true; node >= 0; first = false) {
    const StrategyNode& n = s.nodes[static_cast<std::size_t>(node)];
    os << (first ? "" : ", ") << n.motion;
    if (!n.branches.empty()) {
      os << ", branch {";
      for (std::size_t b = 0; b < n.branches.size(); ++b) {
        const StrategyBranch& br = n.branches[b];
        os << (b ? "; " : "");
        if (br.otherwise)
          os << "else: [";
        else
          os << "when " << test_text(br.when) << ": [";
        write_list(s, br.first, os);
        os << "]";
      }
      os << "}";
    }
    node = n.next;
  }
}

}  // namespace

Strategy chain_strategy(std::vector<std::string> motions) {
  return Strategy::sequence("taught", std::move(motions));
}

Strategy followed_by(const std::string& motion, const Strategy& rest) {
  Strategy out = chain_strategy({motion});
  if (!rest.nodes.empty()) out.nodes[0].next = copy_subtree(rest, 0, out, 0, -1);
  return out;
}

Strategy subtree(const Strategy& strategy, int first) {
  Strategy out;
  out.name = strategy.name;
  if (first >= 0) copy_subtree(strategy, first, out, -1, -1);
  return out;
}

Strategy dispatch(const std::string& motion, const std::vector<DispatchBranch>& branches) {
  if (branches.size() < 2) throw std::invalid_argument("a sensed dispatch needs a test and an else");
  Strategy out = chain_strategy({motion});
  for (std::size_t b = 0; b < branches.size(); ++b) {
    StrategyBranch branch;
    branch.otherwise = b + 1 == branches.size();
    if (!branch.otherwise) branch.when = branches[b].when;
    branch.key = branch.otherwise ? "the dispatch's else" : "the dispatch's test " + std::to_string(b);
    out.nodes[0].branches.push_back(branch);
  }
  for (std::size_t b = 0; b < branches.size(); ++b) {
    const Strategy& then = branches[b].then;
    const int first = then.nodes.empty() ? -1 : copy_subtree(then, 0, out, 0, static_cast<int>(b));
    out.nodes[0].branches[b].first = first;
  }
  return out;
}

bool same_strategy(const Strategy& a, const Strategy& b) {
  if (a.nodes.size() != b.nodes.size()) return false;
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const StrategyNode &x = a.nodes[i], &y = b.nodes[i];
    if (x.motion != y.motion || x.parent != y.parent || x.branch != y.branch || x.next != y.next ||
        x.branches.size() != y.branches.size())
      return false;
    for (std::size_t k = 0; k < x.branches.size(); ++k) {
      const StrategyBranch &p = x.branches[k], &q = y.branches[k];
      if (p.otherwise != q.otherwise || p.first != q.first || !same_termination(p.when, q.when)) return false;
    }
  }
  return true;
}

std::string strategy_text(const Strategy& strategy) {
  std::ostringstream os;
  write_list(strategy, strategy.nodes.empty() ? -1 : 0, os);
  return os.str();
}

}  // namespace cmt::teaching
