#include "planner/ocp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace centaur::planner {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// An element must not read the same decision variable twice (the Hessian assembly relies on it).
void checkUniqueInputs(std::vector<int> in, const char* name) {
  std::sort(in.begin(), in.end());
  if (std::adjacent_find(in.begin(), in.end()) != in.end())
    throw std::invalid_argument(std::string("Ocp: element ") + name + " reads a variable twice");
}
}  // namespace

Ocp::Ocp(int num_intervals) : N_(num_intervals) {
  if (N_ < 1) throw std::invalid_argument("Ocp: at least one interval");
}

void Ocp::addState(const std::string& name, int size) {
  if (vectors_sized_) throw std::logic_error("Ocp: add variables before setting bounds/guesses");
  vars_.push_back({name, true, nx_, size});
  nx_ += size;
}

void Ocp::addControl(const std::string& name, int size) {
  if (vectors_sized_) throw std::logic_error("Ocp: add variables before setting bounds/guesses");
  vars_.push_back({name, false, nu_, size});
  nu_ += size;
}

const Ocp::Var& Ocp::var(const std::string& name) const {
  for (const auto& v : vars_)
    if (v.name == name) return v;
  throw std::invalid_argument("Ocp: unknown variable '" + name + "'");
}

bool Ocp::isState(const std::string& name) const { return var(name).state; }
int Ocp::size(const std::string& name) const { return var(name).size; }

void Ocp::checkNode(const Var& v, int k) const {
  const int last = v.state ? N_ : N_ - 1;
  if (k < 0 || k > last) throw std::out_of_range("Ocp: node " + std::to_string(k) + " out of range for " + v.name);
}

int Ocp::index(const std::string& name, int k, int j) const {
  const Var& v = var(name);
  checkNode(v, k);
  if (j < 0 || j >= v.size) throw std::out_of_range("Ocp: element out of range for " + name);
  return k * (nx_ + nu_) + (v.state ? 0 : nx_) + v.offset + j;
}

std::vector<int> Ocp::indices(const std::string& name, int k) const {
  const Var& v = var(name);
  std::vector<int> out(v.size);
  for (int j = 0; j < v.size; ++j) out[j] = index(name, k, j);
  return out;
}

std::vector<int> Ocp::stateNodes() const {
  std::vector<int> n(N_ + 1);
  for (int k = 0; k <= N_; ++k) n[k] = k;
  return n;
}

std::vector<int> Ocp::controlNodes() const {
  std::vector<int> n(N_);
  for (int k = 0; k < N_; ++k) n[k] = k;
  return n;
}

void Ocp::sizeVectors() {
  if (vectors_sized_) return;
  const int n = numVariables();
  z_lb_ = Eigen::VectorXd::Constant(n, -kInf);
  z_ub_ = Eigen::VectorXd::Constant(n, kInf);
  z0_ = Eigen::VectorXd::Zero(n);
  z_scale_ = Eigen::VectorXd::Ones(n);
  vectors_sized_ = true;
}

void Ocp::setBounds(const std::string& name, int k, const Eigen::VectorXd& lb, const Eigen::VectorXd& ub) {
  sizeVectors();
  const auto idx = indices(name, k);
  if (lb.size() != static_cast<Eigen::Index>(idx.size()) || ub.size() != lb.size())
    throw std::invalid_argument("Ocp::setBounds: size mismatch for " + name);
  for (std::size_t j = 0; j < idx.size(); ++j) {
    z_lb_[idx[j]] = lb[j];
    z_ub_[idx[j]] = ub[j];
  }
}

void Ocp::setBounds(const std::string& name, const std::vector<int>& nodes, const Eigen::VectorXd& lb,
                    const Eigen::VectorXd& ub) {
  for (int k : nodes) setBounds(name, k, lb, ub);
}

void Ocp::setGuess(const std::string& name, int k, const Eigen::VectorXd& value) {
  sizeVectors();
  const auto idx = indices(name, k);
  if (value.size() != static_cast<Eigen::Index>(idx.size()))
    throw std::invalid_argument("Ocp::setGuess: size mismatch for " + name);
  for (std::size_t j = 0; j < idx.size(); ++j) z0_[idx[j]] = value[j];
}

void Ocp::setScale(const std::string& name, const Eigen::VectorXd& scale) {
  sizeVectors();
  const Var& v = var(name);
  if (scale.size() != v.size) throw std::invalid_argument("Ocp::setScale: size mismatch for " + name);
  const int last = v.state ? N_ : N_ - 1;
  for (int k = 0; k <= last; ++k)
    for (int j = 0; j < v.size; ++j) z_scale_[index(name, k, j)] = scale[j];
}

const Ocp::ConstraintBlock& Ocp::addConstraint(const std::string& name, int k, const Eigen::VectorXd& lb,
                                               const Eigen::VectorXd& ub) {
  if (finalized_) throw std::logic_error("Ocp: finalized");
  if (lb.size() != ub.size()) throw std::invalid_argument("Ocp::addConstraint: bound sizes differ");
  ConstraintBlock b{name, k, m_, static_cast<int>(lb.size())};
  m_ += b.rows;
  g_lb_.conservativeResize(m_);
  g_ub_.conservativeResize(m_);
  g_lb_.tail(b.rows) = lb;
  g_ub_.tail(b.rows) = ub;
  blocks_.push_back(b);
  return blocks_.back();
}

void Ocp::addTerm(const ConstraintBlock& block, std::shared_ptr<const Element> element, const std::vector<int>& inputs,
                  std::vector<int> rows) {
  if (finalized_) throw std::logic_error("Ocp: finalized");
  if (static_cast<int>(inputs.size()) != element->numInputs())
    throw std::invalid_argument(std::string("Ocp::addTerm: input count mismatch for ") + element->name());
  if (rows.empty()) {
    for (int j = 0; j < element->numOutputs(); ++j) rows.push_back(j);
  }
  if (static_cast<int>(rows.size()) != element->numOutputs())
    throw std::invalid_argument(std::string("Ocp::addTerm: output count mismatch for ") + element->name());
  checkUniqueInputs(inputs, element->name());
  Instance inst;
  inst.element = std::move(element);
  inst.in = inputs;
  for (int r : rows) {
    if (r < 0 || r >= block.rows) throw std::out_of_range("Ocp::addTerm: row outside block " + block.name);
    inst.out_rows.push_back(block.first_row + r);
  }
  constraint_terms_.push_back(std::move(inst));
}

void Ocp::addCost(const std::string& name, std::shared_ptr<const Element> element, const std::vector<int>& inputs,
                  double weight) {
  if (finalized_) throw std::logic_error("Ocp: finalized");
  if (static_cast<int>(inputs.size()) != element->numInputs())
    throw std::invalid_argument(std::string("Ocp::addCost: input count mismatch for ") + element->name());
  if (weight == 0.0) return;
  checkUniqueInputs(inputs, element->name());
  Instance inst;
  inst.element = std::move(element);
  inst.in = inputs;
  inst.weight = weight;
  inst.cost_name = name;
  cost_terms_.push_back(std::move(inst));
}

const Ocp::Pattern& Ocp::pattern(const Element& e, std::map<const Element*, Pattern>& cache) {
  auto found = cache.find(&e);
  if (found != cache.end()) return found->second;
  const int ni = e.numInputs(), no = e.numOutputs();
  // Structural pattern from the union of two random evaluation points (accidental zeros are improbable).
  // It depends on the element only, so it is computed once per Element object and shared by its instances.
  std::mt19937 rng(12345u + static_cast<unsigned>(ni * 131 + no));
  std::uniform_real_distribution<double> U(0.3, 1.1);
  std::vector<double> in(ni), out(no), jac(no * ni), w(no), hess(ni * ni);
  Pattern p;
  p.jnz.assign(no * ni, 0);
  p.hnz.assign(ni * ni, 0);
  for (int trial = 0; trial < 2; ++trial) {
    for (auto& v : in) v = U(rng) * (trial ? -1.0 : 1.0);
    for (auto& v : w) v = U(rng);
    e.evalJacobian(in.data(), out.data(), jac.data());
    for (int i = 0; i < no * ni; ++i) p.jnz[i] |= (jac[i] != 0.0);
    e.evalHessian(in.data(), w.data(), hess.data());
    for (int i = 0; i < ni * ni; ++i) p.hnz[i] |= (hess[i] != 0.0);
  }
  return cache.emplace(&e, std::move(p)).first->second;
}

void Ocp::analyze(Instance& inst, const Pattern& p, std::map<std::pair<int, int>, int>& jac_map,
                  std::map<std::pair<int, int>, int>& hess_map, bool constraint) {
  const Element& e = *inst.element;
  const int ni = e.numInputs(), no = e.numOutputs();
  const std::vector<char>& jnz = p.jnz;
  const std::vector<char>& hnz = p.hnz;
  if (constraint) {
    inst.jac_slot.assign(no * ni, -1);
    for (int j = 0; j < no; ++j)
      for (int i = 0; i < ni; ++i) {
        if (!jnz[j * ni + i]) continue;
        const auto key = std::make_pair(inst.out_rows[j], inst.in[i]);
        auto it = jac_map.find(key);
        if (it == jac_map.end()) it = jac_map.emplace(key, static_cast<int>(jac_map.size())).first;
        inst.jac_slot[j * ni + i] = it->second;
      }
  }
  inst.hess_slot.assign(ni * ni, -1);
  for (int a = 0; a < ni; ++a)
    for (int b = 0; b < ni; ++b) {
      if (!hnz[a * ni + b]) continue;
      const int r = inst.in[a], c = inst.in[b];
      if (r < c) continue;  // lower triangle only; (a,b) with r == c appears once per pair a==b or duplicates
      if (r == c && a > b) continue;
      const auto key = std::make_pair(r, c);
      auto it = hess_map.find(key);
      if (it == hess_map.end()) it = hess_map.emplace(key, static_cast<int>(hess_map.size())).first;
      inst.hess_slot[a * ni + b] = it->second;
      inst.has_hessian = true;
    }
}

void Ocp::finalize() {
  if (finalized_) return;
  sizeVectors();
  std::map<std::pair<int, int>, int> jac_map, hess_map;
  std::map<const Element*, Pattern> patterns;
  std::size_t max_in = 1, max_out = 1;
  for (auto& t : constraint_terms_) {
    analyze(t, pattern(*t.element, patterns), jac_map, hess_map, true);
    max_in = std::max(max_in, t.in.size());
    max_out = std::max(max_out, t.out_rows.size());
  }
  for (auto& t : cost_terms_) {
    analyze(t, pattern(*t.element, patterns), jac_map, hess_map, false);
    max_in = std::max(max_in, t.in.size());
    max_out = std::max<std::size_t>(max_out, t.element->numOutputs());
  }
  // Renumber slots in (row, col) order: Ipopt does not need it, but it makes the structure reproducible.
  std::vector<int> jac_perm(jac_map.size()), hess_perm(hess_map.size());
  jac_rows_.clear();
  jac_cols_.clear();
  int n = 0;
  for (auto& [key, slot] : jac_map) {
    jac_perm[slot] = n++;
    jac_rows_.push_back(key.first);
    jac_cols_.push_back(key.second);
  }
  n = 0;
  hess_rows_.clear();
  hess_cols_.clear();
  for (auto& [key, slot] : hess_map) {
    hess_perm[slot] = n++;
    hess_rows_.push_back(key.first);
    hess_cols_.push_back(key.second);
  }
  auto remap = [](std::vector<int>& slots, const std::vector<int>& perm) {
    for (auto& s : slots)
      if (s >= 0) s = perm[s];
  };
  for (auto& t : constraint_terms_) {
    remap(t.jac_slot, jac_perm);
    remap(t.hess_slot, hess_perm);
  }
  for (auto& t : cost_terms_) remap(t.hess_slot, hess_perm);
  auto compact = [](const std::vector<int>& slots, std::vector<std::pair<int, int>>& nz) {
    nz.clear();
    for (std::size_t k = 0; k < slots.size(); ++k)
      if (slots[k] >= 0) nz.emplace_back(static_cast<int>(k), slots[k]);
  };
  for (auto& t : constraint_terms_) {
    compact(t.jac_slot, t.jac_nz);
    compact(t.hess_slot, t.hess_nz);
  }
  for (auto& t : cost_terms_) compact(t.hess_slot, t.hess_nz);
  buf_in_.resize(max_in);
  buf_out_.resize(max_out);
  buf_jac_.resize(max_in * max_out);
  buf_hess_.resize(max_in * max_in);
  buf_w_.resize(max_out);
  max_in_ = max_in;
  max_out_ = max_out;
  cacheConstantDerivatives();
  finalized_ = true;
}

// Linear constraint terms (constant Jacobian) and quadratic costs (constant Hessian) are evaluated once here.
void Ocp::cacheConstantDerivatives() {
  const_jac_.assign(jac_rows_.size(), 0.0);
  const_cost_hess_.assign(hess_rows_.size(), 0.0);
  for (auto& t : constraint_terms_) {
    t.const_jac = t.element->jacobianIsConstant() && !t.has_hessian;
    if (!t.const_jac) continue;
    const int ni = static_cast<int>(t.in.size()), no = static_cast<int>(t.out_rows.size());
    for (int i = 0; i < ni; ++i) buf_in_[i] = z0_[t.in[i]];
    t.element->evalJacobian(buf_in_.data(), buf_out_.data(), buf_jac_.data());
    for (int k = 0; k < no * ni; ++k)
      if (t.jac_slot[k] >= 0) const_jac_[t.jac_slot[k]] += buf_jac_[k];
  }
  for (auto& t : cost_terms_) {
    t.const_hess = t.element->hessianIsConstant() && t.has_hessian;
    if (!t.const_hess) continue;
    const int ni = static_cast<int>(t.in.size()), no = t.element->numOutputs();
    for (int i = 0; i < ni; ++i) buf_in_[i] = z0_[t.in[i]];
    for (int j = 0; j < no; ++j) buf_w_[j] = t.weight;
    t.element->evalHessian(buf_in_.data(), buf_w_.data(), buf_hess_.data());
    scatterHessian(t, buf_hess_.data(), 1.0, const_cost_hess_.data());
  }
}

void Ocp::scatterHessian(const Instance& t, const double* h, double scale, double* values) const {
  // each lower-triangle pair maps to one slot (see analyze)
  for (const auto& [k, slot] : t.hess_nz) values[slot] += scale * h[k];
}

void Ocp::addConstantDerivatives(double sigma, double* jac, double* hess) const {
  for (std::size_t k = 0; k < const_jac_.size(); ++k) jac[k] += const_jac_[k];
  if (sigma != 0.0)
    for (std::size_t k = 0; k < const_cost_hess_.size(); ++k) hess[k] += sigma * const_cost_hess_[k];
}

double Ocp::termWork(TermRef r) const {
  const Instance& t = r.cost ? cost_terms_[r.index] : constraint_terms_[r.index];
  const double ni = static_cast<double>(t.in.size()), no = static_cast<double>(t.element->numOutputs());
  if (!r.cost && t.const_jac) return 0.0;
  return ni * no + (t.has_hessian && !t.const_hess ? ni * ni : 0.0);
}

void Ocp::footprint(TermRef r, Footprint& f) const {
  const Instance& t = r.cost ? cost_terms_[r.index] : constraint_terms_[r.index];
  f.jac.clear();
  f.hess.clear();
  f.grad.clear();
  if (!r.cost && t.const_jac) return;
  if (r.cost) f.grad = t.in;
  else
    for (const auto& [k, slot] : t.jac_nz) f.jac.push_back(slot);
  if (t.has_hessian && !t.const_hess)
    for (const auto& [k, slot] : t.hess_nz) f.hess.push_back(slot);
}

void Ocp::addDerivatives(const double* z, double sigma, const double* lambda, const std::vector<TermRef>& terms,
                         Scratch& s, double* grad, double* jac, double* hess) const {
  s.in.resize(max_in_);
  s.out.resize(max_out_);
  s.jac.resize(max_in_ * max_out_);
  s.hess.resize(max_in_ * max_in_);
  s.w.resize(max_out_);
  for (const TermRef& r : terms) {
    const Instance& t = r.cost ? cost_terms_[r.index] : constraint_terms_[r.index];
    if (r.cost) {
      addCostTerm(t, z, sigma, s, grad, hess);
    } else if (!t.const_jac) {
      addConstraintTerm(t, z, lambda, s, jac, hess);
    }
  }
}

void Ocp::addConstraintTerm(const Instance& t, const double* z, const double* lambda, Scratch& s, double* jac,
                            double* hess) const {
  const int ni = static_cast<int>(t.in.size()), no = static_cast<int>(t.out_rows.size());
  for (int i = 0; i < ni; ++i) s.in[i] = z[t.in[i]];
  bool any = false;
  for (int j = 0; j < no; ++j) {
    s.w[j] = lambda[t.out_rows[j]];
    any = any || s.w[j] != 0.0;
  }
  if (t.has_hessian && any) {
    t.element->evalJacobianHessian(s.in.data(), s.w.data(), s.out.data(), s.jac.data(), s.hess.data());
    scatterHessian(t, s.hess.data(), 1.0, hess);
  } else {
    t.element->evalJacobian(s.in.data(), s.out.data(), s.jac.data());
  }
  for (const auto& [k, slot] : t.jac_nz) jac[slot] += s.jac[k];
}

void Ocp::addCostTerm(const Instance& t, const double* z, double sigma, Scratch& s, double* grad, double* hess) const {
  const int ni = static_cast<int>(t.in.size()), no = t.element->numOutputs();
  for (int i = 0; i < ni; ++i) s.in[i] = z[t.in[i]];
  for (int j = 0; j < no; ++j) s.w[j] = sigma * t.weight;
  if (t.has_hessian && !t.const_hess && sigma != 0.0) {
    t.element->evalJacobianHessian(s.in.data(), s.w.data(), s.out.data(), s.jac.data(), s.hess.data());
    scatterHessian(t, s.hess.data(), 1.0, hess);
  } else {
    t.element->evalJacobian(s.in.data(), s.out.data(), s.jac.data());
  }
  // The weighted gradient is rounded before it is added (a separate loop, which the compiler does not fuse into
  // a multiply-add): every addition into grad is then the same on any build, so moving a term between the
  // derivative lists (OcpNlp::splitTerms) changes no result with FMA either.
  for (int k = 0; k < no * ni; ++k) s.jac[k] *= t.weight;
  for (int j = 0; j < no; ++j)
    for (int i = 0; i < ni; ++i) grad[t.in[i]] += s.jac[j * ni + i];
}

double Ocp::objective(const double* z) const {
  double f = 0.0;
  for (const auto& t : cost_terms_) {
    const int ni = static_cast<int>(t.in.size()), no = t.element->numOutputs();
    for (int i = 0; i < ni; ++i) buf_in_[i] = z[t.in[i]];
    t.element->eval(buf_in_.data(), buf_out_.data());
    for (int j = 0; j < no; ++j) f += t.weight * buf_out_[j];
  }
  return f;
}

std::map<std::string, double> Ocp::costBreakdown(const double* z) const {
  std::map<std::string, double> out;
  for (const auto& t : cost_terms_) {
    const int ni = static_cast<int>(t.in.size()), no = t.element->numOutputs();
    for (int i = 0; i < ni; ++i) buf_in_[i] = z[t.in[i]];
    t.element->eval(buf_in_.data(), buf_out_.data());
    for (int j = 0; j < no; ++j) out[t.cost_name] += t.weight * buf_out_[j];
  }
  return out;
}

void Ocp::gradient(const double* z, double* grad) const {
  std::fill(grad, grad + numVariables(), 0.0);
  for (const auto& t : cost_terms_) {
    const int ni = static_cast<int>(t.in.size()), no = t.element->numOutputs();
    for (int i = 0; i < ni; ++i) buf_in_[i] = z[t.in[i]];
    t.element->evalJacobian(buf_in_.data(), buf_out_.data(), buf_jac_.data());
    for (int j = 0; j < no; ++j)
      for (int i = 0; i < ni; ++i) grad[t.in[i]] += t.weight * buf_jac_[j * ni + i];
  }
}

void Ocp::constraints(const double* z, double* g) const {
  std::fill(g, g + m_, 0.0);
  for (const auto& t : constraint_terms_) {
    const int ni = static_cast<int>(t.in.size()), no = static_cast<int>(t.out_rows.size());
    for (int i = 0; i < ni; ++i) buf_in_[i] = z[t.in[i]];
    t.element->eval(buf_in_.data(), buf_out_.data());
    for (int j = 0; j < no; ++j) g[t.out_rows[j]] += buf_out_[j];
  }
}

void Ocp::jacobian(const double* z, double* values) const {
  std::copy(const_jac_.begin(), const_jac_.end(), values);
  for (const auto& t : constraint_terms_) {
    if (t.const_jac) continue;
    const int ni = static_cast<int>(t.in.size()), no = static_cast<int>(t.out_rows.size());
    for (int i = 0; i < ni; ++i) buf_in_[i] = z[t.in[i]];
    t.element->evalJacobian(buf_in_.data(), buf_out_.data(), buf_jac_.data());
    for (int k = 0; k < no * ni; ++k)
      if (t.jac_slot[k] >= 0) values[t.jac_slot[k]] += buf_jac_[k];
  }
}

void Ocp::hessian(const double* z, double sigma, const double* lambda, double* values) const {
  std::fill(values, values + hessianNonzeros(), 0.0);
  auto accumulate = [&](const Instance& t) {
    const int ni = static_cast<int>(t.in.size());
    for (int i = 0; i < ni; ++i) buf_in_[i] = z[t.in[i]];
    t.element->evalHessian(buf_in_.data(), buf_w_.data(), buf_hess_.data());
    for (int a = 0; a < ni; ++a)
      for (int b = 0; b < ni; ++b) {
        const int s = t.hess_slot[a * ni + b];
        if (s < 0) continue;
        // Off-diagonal pairs (a,b) and (b,a) map to one lower-triangle slot only from the (r >= c) side;
        // the symmetric partner was skipped, so the entry is H[a][b] once.
        values[s] += buf_hess_[a * ni + b];
      }
  };
  for (const auto& t : constraint_terms_) {
    if (!t.has_hessian) continue;
    const int no = static_cast<int>(t.out_rows.size());
    bool any = false;
    for (int j = 0; j < no; ++j) {
      buf_w_[j] = lambda[t.out_rows[j]];
      any = any || buf_w_[j] != 0.0;
    }
    if (any) accumulate(t);
  }
  if (sigma != 0.0) {
    for (std::size_t k = 0; k < const_cost_hess_.size(); ++k) values[k] += sigma * const_cost_hess_[k];
    for (const auto& t : cost_terms_) {
      if (!t.has_hessian || t.const_hess) continue;
      const int no = t.element->numOutputs();
      for (int j = 0; j < no; ++j) buf_w_[j] = sigma * t.weight;
      accumulate(t);
    }
  }
}

}  // namespace centaur::planner
