#pragma once
// Template definitions of Parameters (included by parameters.hpp).
#include <type_traits>

namespace ltm::runtime {

template <>
inline const char* yaml_type_name<bool>() {
    return "true or false";
}
template <>
inline const char* yaml_type_name<int>() {
    return "an integer";
}
template <>
inline const char* yaml_type_name<long>() {
    return "an integer";
}
template <>
inline const char* yaml_type_name<unsigned>() {
    return "a non-negative integer";
}
template <>
inline const char* yaml_type_name<std::size_t>() {
    return "a non-negative integer";
}
template <>
inline const char* yaml_type_name<float>() {
    return "a number";
}
template <>
inline const char* yaml_type_name<double>() {
    return "a number";
}
template <>
inline const char* yaml_type_name<std::string>() {
    return "a string";
}
template <>
inline const char* yaml_type_name<std::vector<double>>() {
    return "a list of numbers";
}
template <>
inline const char* yaml_type_name<std::vector<std::string>>() {
    return "a list of strings";
}

template <class T>
T Parameters::convert(const std::string& key, const YAML::Node& node) {
    const bool want_scalar = std::is_arithmetic_v<T> || std::is_same_v<T, std::string>;
    if (want_scalar && !node.IsScalar()) fail(key, std::string("expected ") + yaml_type_name<T>());
    if (!want_scalar && !node.IsSequence())
        fail(key, std::string("expected ") + yaml_type_name<T>());
    try {
        if constexpr (std::is_same_v<T, std::string>) {
            return expand_env(node.as<std::string>());
        } else if constexpr (std::is_unsigned_v<T> && !std::is_same_v<T, bool>) {
            if (!node.Scalar().empty() && node.Scalar()[0] == '-')
                throw YAML::BadConversion(node.Mark());
            return node.as<T>();
        } else {
            return node.as<T>();
        }
    } catch (const YAML::Exception&) {
        fail(key, std::string("expected ") + yaml_type_name<T>() + ", got '" +
                      (node.IsScalar() ? node.Scalar() : std::string("...")) + "'");
    }
}

template <class T>
T Parameters::get(const std::string& key, const T& fallback) {
    used_->insert(key);
    const YAML::Node node = lookup(key);
    if (!node.IsDefined() || node.IsNull()) return fallback;
    return convert<T>(key, node);
}

template <class T>
T Parameters::require(const std::string& key) {
    used_->insert(key);
    const YAML::Node node = lookup(key);
    if (!node.IsDefined() || node.IsNull()) fail(key, "required parameter is missing");
    return convert<T>(key, node);
}

}  // namespace ltm::runtime
