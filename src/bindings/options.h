// Options structs for Python, each field registered once (ARCHITECTURE.md, "Options defined
// once"). OptionsClass<T> binds T with a keyword-only __init__(**kwargs) that takes exactly the
// registered fields. A field left out keeps its value in a default-constructed T{}, so the
// defaults live in the C++ struct alone. A field given is converted and checked against its Range
// as it is set: a bad value is a ValueError naming the field, an unknown keyword a TypeError that
// lists the valid ones. Then T::validate(), where T has one, checks what involves several fields
// (it throws std::invalid_argument, a ValueError in Python), so the C++ API can check the same.
// Fields are read-only properties with docstrings; __repr__ shows them, `_fields` names them in
// order (Python asks a class which options it takes instead of keeping a list of its own), and
// __init__'s docstring carries the typed signature with the defaults, for help() and the stub.
#pragma once
#include <pybind11/pybind11.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace dualight::bindings {

namespace py = pybind11;

// The values a numeric field takes: from min to max, an end excluded when open or absent when
// unset (integers: the type's own limits). `why` is said after the range in the error;
// `why_max` only when an integer is above max.
struct Range {
  std::optional<double> min, max;
  bool min_open = false, max_open = false;
  const char* why = nullptr;
  const char* why_max = nullptr;
};
inline Range up_to(double min, double max, const char* why_max) { return {min, max, false, false, nullptr, why_max}; }
inline Range at_least(double min) { return {min, std::nullopt}; }
inline Range above(double min, const char* why = nullptr) { return {min, std::nullopt, true, false, why}; }
inline Range within(double min, double max) { return {min, max}; }                 // [min, max]
inline Range strictly_within(double min, double max) { return {min, max, true, true}; }  // (min, max)

// A field chosen by name in Python: each name and the value it stands for.
template <class V>
using Names = std::vector<std::pair<std::string, V>>;

namespace options_detail {

inline std::string repr_of(py::handle value) { return py::repr(value).cast<std::string>(); }

// The shortest decimal that reads back as `v` in its own type (0.01f is "0.01").
template <class V>
std::string decimal(V v) {
  char text[64];
  const char* end = std::to_chars(text, text + sizeof text, v).ptr;
  return std::string(static_cast<const char*>(text), end);
}

// `v` as Python source: a float keeps its decimal point (1.0, not 1).
template <class V>
std::string python_number(V v) {
  std::string s = decimal(v);
  if (std::is_floating_point_v<V> && s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

// " >= 0", " > 0", " in (0, 1)", " in [0, 1]", or "" without bounds.
template <class V>
std::string range_text(const Range& r) {
  const auto bound = [](double b) { return decimal(static_cast<V>(b)); };
  if (r.min && r.max) {
    return std::string(" in ") + (r.min_open ? "(" : "[") + bound(*r.min) + ", " + bound(*r.max) +
           (r.max_open ? ")" : "]");
  }
  if (r.min) return (r.min_open ? " > " : " >= ") + bound(*r.min);
  if (r.max) return (r.max_open ? " < " : " <= ") + bound(*r.max);
  return "";
}

[[noreturn]] inline void bad_value(const std::string& name, const std::string& expected, const Range& r,
                                   py::handle value) {
  throw py::value_error(name + " must be " + expected + (r.why ? std::string(" ") + r.why : std::string()) +
                        ", got " + repr_of(value));
}

// An integer (not a bool, not a float) within the range and the type's limits.
template <class V>
V to_integer(const std::string& name, py::handle value, const Range& r) {
  const V lo = r.min ? static_cast<V>(*r.min) : std::numeric_limits<V>::lowest();
  const V hi = r.max ? static_cast<V>(*r.max) : std::numeric_limits<V>::max();
  const std::string at_least_lo = "an integer >= " + decimal(lo);
  if (PyBool_Check(value.ptr()) || !PyIndex_Check(value.ptr())) bad_value(name, at_least_lo, r, value);
  const auto i = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
  if (!i) {
    PyErr_Clear();
    bad_value(name, at_least_lo, r, value);
  }
  if (i < py::int_(lo)) bad_value(name, at_least_lo, r, value);
  if (i > py::int_(hi)) {
    bad_value(name, "an integer <= " + decimal(hi), r.why_max ? Range{r.min, r.max, false, false, r.why_max} : r,
              value);
  }
  return i.template cast<V>();
}

// A finite real number (not a bool) within the range, compared in the field's own type.
template <class V>
V to_real(const std::string& name, py::handle value, const Range& r) {
  const std::string range = range_text<V>(r);
  double d = std::numeric_limits<double>::quiet_NaN();
  if (!PyBool_Check(value.ptr()) && PyNumber_Check(value.ptr())) {
    d = PyFloat_AsDouble(value.ptr());
    if (PyErr_Occurred()) {
      PyErr_Clear();
      d = std::numeric_limits<double>::quiet_NaN();
    }
  }
  if (!(std::abs(d) <= static_cast<double>(std::numeric_limits<V>::max()))) {
    bad_value(name, "a finite number" + range, r, value);
  }
  const V v = static_cast<V>(d);
  const bool low = r.min && (r.min_open ? !(v > static_cast<V>(*r.min)) : !(v >= static_cast<V>(*r.min)));
  const bool high = r.max && (r.max_open ? !(v < static_cast<V>(*r.max)) : !(v <= static_cast<V>(*r.max)));
  if (low || high) bad_value(name, range.substr(1), r, value);
  return v;
}

inline bool to_bool(const std::string& name, py::handle value) {
  const char* type = Py_TYPE(value.ptr())->tp_name;
  if (!PyBool_Check(value.ptr()) && std::strcmp(type, "numpy.bool_") != 0 && std::strcmp(type, "numpy.bool") != 0) {
    throw py::type_error(name + " must be True or False, got " + repr_of(value));
  }
  return PyObject_IsTrue(value.ptr()) == 1;
}

// One of `names`, given by name (or, for an enum bound by py::enum_, as its member).
template <class V>
V to_named(const std::string& name, py::handle value, const Names<V>& names) {
  const py::handle type = py::detail::get_type_handle(typeid(V), false);  // none for a choice
  if (type && py::isinstance(value, type)) return value.cast<V>();
  if (py::isinstance<py::str>(value)) {
    const std::string given = value.cast<std::string>();
    for (const auto& [n, v] : names) {
      if (n == given) return v;
    }
  }
  std::string valid;
  for (const auto& entry : names) valid += (valid.empty() ? "'" : ", '") + entry.first + "'";
  throw py::value_error(name + " must be one of " + valid + ", got " + repr_of(value));
}

// The Python type of an enum bound by py::enum_ (bound before the options that use it).
template <class V>
py::handle enum_type() {
  return py::detail::get_type_handle(typeid(V), true);
}

// The members of an enum bound by py::enum_, by name.
template <class V>
Names<V> enum_names() {
  Names<V> names;
  const py::dict members = enum_type<V>().attr("__members__");
  for (const auto& [n, v] : members) names.emplace_back(n.template cast<std::string>(), v.template cast<V>());
  return names;
}

template <class T, class = void>
struct has_validate : std::false_type {};
template <class T>
struct has_validate<T, std::void_t<decltype(std::declval<const T&>().validate())>> : std::true_type {};

template <class T>
struct Field {
  std::string name, annotation, doc;
  std::function<void(T&, py::handle)> set;      // converts, checks and assigns
  std::function<std::string(const T&)> source;  // the value as Python source
};

}  // namespace options_detail

template <class T>
class OptionsClass {
 public:
  OptionsClass(py::module_& m, const char* name, const char* doc) : cls_(m, name, doc), doc_(doc) {}

  // A number or a bool; an enum bound by py::enum_ takes its members or their names.
  template <class V, class Owner>
  OptionsClass& field(const char* name, V Owner::*member, const char* doc, const Range& range = {}) {
    using namespace options_detail;
    static_assert(std::is_base_of_v<Owner, T>, "a field of T or of a base of T");
    if constexpr (std::is_same_v<V, bool>) {
      add(name, member, doc, "bool", to_bool, [](bool v) { return std::string(v ? "True" : "False"); });
    } else if constexpr (std::is_integral_v<V>) {
      add(name, member, doc, "int", [range](const std::string& n, py::handle v) { return to_integer<V>(n, v, range); },
          [](V v) { return decimal(v); });
    } else if constexpr (std::is_floating_point_v<V>) {
      add(name, member, doc, "float", [range](const std::string& n, py::handle v) { return to_real<V>(n, v, range); },
          [](V v) { return python_number(v); });
    } else {
      static_assert(std::is_enum_v<V>, "options are numbers, bools or enums");
      const Names<V> names = enum_names<V>();
      const std::string type = enum_type<V>().attr("__name__").template cast<std::string>();
      add(name, member, doc, type + " | str",
          [names](const std::string& n, py::handle v) { return to_named<V>(n, v, names); },
          [](V v) { return py::str(py::cast(v)).template cast<std::string>(); });
    }
    cls_.def_property_readonly(name, [member](const T& o) { return o.*member; }, doc);
    return *this;
  }

  // An enum without a Python type: set and read by the names given.
  template <class V, class Owner>
  OptionsClass& choice(const char* name, V Owner::*member, const char* doc, Names<V> names) {
    using namespace options_detail;
    static_assert(std::is_base_of_v<Owner, T>, "a field of T or of a base of T");
    const auto name_of = [names](V v) {
      const auto it = std::find_if(names.begin(), names.end(), [v](const auto& e) { return e.second == v; });
      return it->first;
    };
    add(name, member, doc, "str", [names](const std::string& n, py::handle v) { return to_named<V>(n, v, names); },
        [name_of](V v) { return "'" + name_of(v) + "'"; });
    cls_.def_property_readonly(name, [member, name_of](const T& o) { return name_of(o.*member); }, doc);
    return *this;
  }

  // The constructor, __repr__ and _fields, once every field is added.
  void bind() {
    const auto fields = fields_;
    const std::string cls_name = cls_.attr("__name__").template cast<std::string>();
    {
      py::options docstring_only;  // the signature below replaces pybind11's (**kwargs)
      docstring_only.disable_function_signatures();
      const std::string doc = init_doc(cls_name);
      cls_.def(py::init([fields, cls_name](const py::kwargs& kwargs) { return make(*fields, cls_name, kwargs); }),
               doc.c_str());
    }
    cls_.def("__repr__", [fields, cls_name](const T& o) {
      std::string s;
      for (const auto& f : *fields) s += (s.empty() ? "" : ", ") + f.name + "=" + f.source(o);
      return cls_name + "(" + s + ")";
    });
    py::tuple names(fields->size());
    for (size_t k = 0; k < fields->size(); ++k) names[k] = py::str((*fields)[k].name);
    cls_.attr("_fields") = names;
  }

 private:
  template <class V, class Owner, class Convert, class Source>
  void add(const char* name, V Owner::*member, const char* doc, std::string annotation, Convert convert,
           Source source) {
    const std::string n = name;
    fields_->push_back({n, std::move(annotation), doc,
                        [member, convert, n](T& o, py::handle v) { o.*member = convert(n, v); },
                        [member, source](const T& o) { return source(o.*member); }});
  }

  static T make(const std::vector<options_detail::Field<T>>& fields, const std::string& cls_name,
                const py::kwargs& kwargs) {
    T o{};
    for (const auto& [key, value] : kwargs) {
      const std::string k = py::str(key);
      const auto f = std::find_if(fields.begin(), fields.end(), [&k](const auto& field) { return field.name == k; });
      if (f == fields.end()) {
        std::string valid;
        for (const auto& field : fields) valid += (valid.empty() ? "" : ", ") + field.name;
        throw py::type_error("unknown option '" + k + "' for " + cls_name + "; valid: " + valid);
      }
      f->set(o, value);
    }
    if constexpr (options_detail::has_validate<T>::value) o.validate();
    return o;
  }

  // "__init__(self, *, spp: int = 64, ...) -> None", then the class's doc and each field's.
  std::string init_doc(const std::string& cls_name) const {
    const T defaults{};
    std::string signature, fields;
    for (const auto& f : *fields_) {
      signature += ", " + f.name + ": " + f.annotation + " = " + f.source(defaults);
      fields += "\n" + f.name + ": " + f.doc;
    }
    return "__init__(self, *" + signature + ") -> None\n\n" + doc_ + " Keywords only: an option left out keeps " +
           "its default above (the C++ " + cls_name + "{}); an unknown one is a TypeError, a bad value a " +
           "ValueError naming it.\n" + fields;
  }

  py::class_<T> cls_;
  std::string doc_;
  std::shared_ptr<std::vector<options_detail::Field<T>>> fields_ = std::make_shared<std::vector<options_detail::Field<T>>>();
};

}  // namespace dualight::bindings
