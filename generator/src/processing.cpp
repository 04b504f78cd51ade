#include "processing.hpp"

namespace erkn::gen {

Qs Processor::total() const {
  Qs sum(0);
  for (const Qs& z : drift) sum = sum + z;
  return sum;
}

KickSequence composition(const std::vector<Qs>& c, const std::vector<Qs>& d,
                         const std::vector<Qs>& e, const Processor& pre) {
  if (pre.empty()) return {c, d, e};
  const bool modified = !e.empty() || !pre.modified.empty();
  auto e_of = [](const std::vector<Qs>& list, size_t i) { return list.empty() ? Qs(0) : list[i]; };
  std::vector<Qs> at;  // the pre-sequence's kick positions
  Qs position(0);
  for (size_t k = 0; k < pre.kick.size(); ++k) at.push_back(position = position + pre.drift[k]);
  const Qs T = pre.total();
  KickSequence out;
  auto add = [&](const Qs& ci, const Qs& di, const Qs& ei) {
    out.c.push_back(ci), out.d.push_back(di);
    if (modified) out.e.push_back(ei);
  };
  for (size_t k = 0; k < at.size(); ++k) add(at[k], pre.kick[k], e_of(pre.modified, k));
  for (size_t i = 0; i < c.size(); ++i) add(T + c[i], d[i], e_of(e, i));
  for (size_t k = at.size(); k-- > 0;) add(Qs(1) + at[k], -pre.kick[k], -e_of(pre.modified, k));
  return out;
}

}  // namespace erkn::gen
