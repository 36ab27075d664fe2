#include "models/model_error.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <regex>
#include <stdexcept>

#include "models/task.h"

namespace cmt {
namespace {

// Values closer than this fraction of the interval's length are one slice value.
constexpr double kSliceValueRelativeTolerance = 1e-12;

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

bool parse_number(const std::string& text, double* out) {
  if (text.empty()) return false;
  std::size_t used = 0;
  try {
    *out = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size() && std::isfinite(*out);
}

// One term without its sign: "2", "w", "2*w", "w*2".
void add_term(const std::string& raw, double sign, const std::vector<ModelParameter>& parameters,
              AffineValue* value) {
  const std::string term = trim(raw);
  if (term.empty()) throw std::invalid_argument("an empty term");
  double number = 0;
  if (parse_number(term, &number)) {
    value->constant += sign * number;
    return;
  }
  std::string name = term;
  double factor = 1;
  if (const auto star = term.find('*'); star != std::string::npos) {
    const std::string a = trim(term.substr(0, star)), b = trim(term.substr(star + 1));
    if (parse_number(a, &factor))
      name = b;
    else if (parse_number(b, &factor))
      name = a;
    else
      throw std::invalid_argument("term '" + term + "' is not a number times a parameter");
    if (!name.empty() && name[0] == '-') {  // "2*-w"
      factor = -factor;
      name = trim(name.substr(1));
    }
  }
  for (std::size_t i = 0; i < parameters.size(); ++i)
    if (parameters[i].name == name) {
      value->coefficients[i] += sign * factor;
      return;
    }
  std::string known;
  for (const ModelParameter& p : parameters) known += (known.empty() ? "" : ", ") + p.name;
  throw std::invalid_argument("unknown model parameter '" + name + "' (model_error has: " + known + ")");
}

}  // namespace

double AffineValue::at(const std::vector<double>& values) const {
  double v = constant;
  for (std::size_t i = 0; i < coefficients.size() && i < values.size(); ++i) v += coefficients[i] * values[i];
  return v;
}

bool AffineValue::is_constant() const {
  return std::all_of(coefficients.begin(), coefficients.end(), [](double c) { return c == 0; });
}

AffineValue parse_affine(const std::string& text, const std::vector<ModelParameter>& parameters) {
  AffineValue value{0, std::vector<double>(parameters.size(), 0)};
  std::size_t i = 0;
  const auto skip_spaces = [&] {
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
  };
  skip_spaces();
  if (i == text.size()) throw std::invalid_argument("an empty expression");
  double sign = 1;
  if (text[i] == '+' || text[i] == '-') sign = text[i++] == '-' ? -1 : 1;  // a leading sign
  while (true) {
    // A term runs to the next + or - that is neither an exponent's sign ("1e-3") nor after '*' ("2*-w").
    std::string term;
    for (; i < text.size(); ++i) {
      const char c = text[i];
      if (c == '+' || c == '-') {
        const std::string t = trim(term);
        // The factor being read (after the last '*'): a number's mantissa followed by e or E.
        const std::string factor =
            trim(t.substr(t.find_last_of('*') == std::string::npos ? 0 : t.find_last_of('*') + 1));
        const bool exponent = std::regex_match(factor, std::regex("([0-9]+\\.?[0-9]*|\\.[0-9]+)[eE]"));
        const bool after_star = !t.empty() && t.back() == '*';
        if (!exponent && !after_star) break;
      }
      term += c;
    }
    add_term(term, sign, parameters, &value);
    if (i == text.size()) return value;
    sign = text[i++] == '-' ? -1 : 1;
  }
}

bool ModelParameter::admits(double v) const {
  if (!(v >= min && v <= max)) return false;
  return values.empty() || std::find(values.begin(), values.end(), v) != values.end();
}

std::vector<double> critical_values(const Task& task, std::size_t p) {
  const ModelParameter& param = task.model_error.at(p);
  std::vector<double> roots;
  if (param.discrete()) return roots;
  // Coordinates per axis: the constant ones once each (at the nominal values of the other parameters).
  for (int axis = 0; axis < 3; ++axis) {
    // (value at nominal without p, coefficient of p) per coordinate role.
    std::vector<std::pair<double, double>> forms, environment, robot;
    for (const ModelCoordinate& c : task.model_coordinates) {
      if (c.axis != axis) continue;
      double base = c.value.constant;
      for (std::size_t q = 0; q < task.model_error.size(); ++q)
        if (q != p) base += c.value.coefficients[q] * task.model_error[q].nominal;
      const std::pair<double, double> form(base, c.value.coefficients[p]);
      if (c.role == ModelCoordinate::Role::kEnvironment)
        environment.push_back(form);
      else if (c.role == ModelCoordinate::Role::kRobot)
        robot.push_back(form);
      else
        forms.push_back(form);
    }
    for (auto* list : {&environment, &robot}) {
      std::sort(list->begin(), list->end());
      list->erase(std::unique(list->begin(), list->end()), list->end());
    }
    for (const auto& e : environment)
      for (const auto& r : robot) forms.emplace_back(e.first - r.first, e.second - r.second);
    std::sort(forms.begin(), forms.end());
    forms.erase(std::unique(forms.begin(), forms.end()), forms.end());
    for (std::size_t i = 0; i < forms.size(); ++i)
      for (std::size_t j = i + 1; j < forms.size(); ++j) {
        const double slope = forms[i].second - forms[j].second;
        if (slope == 0) continue;
        const double root = (forms[j].first - forms[i].first) / slope;
        if (root > param.min && root < param.max) roots.push_back(root + 0.0);  // + 0.0: no -0
      }
  }
  std::sort(roots.begin(), roots.end());
  const double tol = kSliceValueRelativeTolerance * std::max(param.max - param.min, 1e-300);
  roots.erase(std::unique(roots.begin(), roots.end(), [&](double a, double b) { return b - a <= tol; }),
              roots.end());
  return roots;
}

std::vector<double> slice_values(const Task& task, std::size_t p, int resolution) {
  const ModelParameter& param = task.model_error.at(p);
  if (resolution < 1) throw std::invalid_argument("the slice resolution must be >= 1");
  if (param.discrete()) return param.values;
  std::vector<double> values;
  if (resolution == 1) {
    values.push_back(param.nominal);
  } else {
    for (int i = 0; i < resolution; ++i)
      values.push_back(i + 1 == resolution ? param.max
                                           : param.min + (param.max - param.min) * i / (resolution - 1));
  }
  std::vector<double> marks = {param.min};
  for (double c : critical_values(task, p)) marks.push_back(c);
  marks.push_back(param.max);
  for (std::size_t i = 1; i + 1 < marks.size(); ++i) values.push_back(marks[i]);
  if (marks.size() > 2)
    for (std::size_t i = 0; i + 1 < marks.size(); ++i) values.push_back((marks[i] + marks[i + 1]) / 2);
  std::sort(values.begin(), values.end());
  const double tol = kSliceValueRelativeTolerance * std::max(param.max - param.min, 1e-300);
  values.erase(std::unique(values.begin(), values.end(), [&](double a, double b) { return b - a <= tol; }),
               values.end());
  return values;
}

std::vector<std::vector<double>> model_slices(const Task& task, int resolution) {
  std::vector<std::vector<double>> slices = {{}};
  for (std::size_t p = 0; p < task.model_error.size(); ++p) {
    const std::vector<double> values = slice_values(task, p, resolution);
    if (slices.size() * values.size() > kMaxModelSlices)
      throw std::invalid_argument("more than " + std::to_string(kMaxModelSlices) +
                                  " slices; lower the resolution");
    std::vector<std::vector<double>> next;
    for (const std::vector<double>& s : slices)
      for (double v : values) {
        next.push_back(s);
        next.back().push_back(v);
      }
    slices = std::move(next);
  }
  return slices;
}

}  // namespace cmt
