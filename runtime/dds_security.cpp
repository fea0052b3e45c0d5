#include "runtime/dds_security.hpp"

#include <dds/dds.h>
#include <dlfcn.h>

#include <filesystem>
#include <stdexcept>

namespace ltm::runtime {
namespace {

namespace fs = std::filesystem;

// `text` with the five XML special characters escaped (paths go into attributes and elements).
std::string xml_escaped(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string library(const std::string& dir, const std::string& plugin, const std::string& init,
                    const std::string& finalize) {
    return "<Library path=\"" + xml_escaped(dir + "/libdds_security_" + plugin + ".so") +
           "\" initFunction=\"" + init + "\" finalizeFunction=\"" + finalize + "\"/>";
}

std::string file_uri(const std::string& path) { return "file:" + xml_escaped(path); }

}  // namespace

std::string dds_security_plugin_dir(std::string* searched) {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&dds_create_domain), &info) == 0 || !info.dli_fname) {
        if (searched) *searched = "(the path of libddsc is unknown)";
        return "";
    }
    std::error_code ec;
    const fs::path lib = fs::canonical(info.dli_fname, ec);
    const fs::path dir = (ec ? fs::path(info.dli_fname) : lib).parent_path();
    const fs::path candidates[] = {dir / "libddsc0debian", dir};
    std::string list;
    for (const auto& c : candidates) {
        bool all = true;
        for (const char* p : {"auth", "ac", "crypto"})
            all = all && fs::is_regular_file(c / ("libdds_security_" + std::string(p) + ".so"), ec);
        if (all) return c.string();
        list += (list.empty() ? "" : ", ") + c.string();
    }
    if (searched) *searched = list;
    return "";
}

std::string dds_security_xml(const DdsSecurity& s) {
    std::string searched;
    const std::string dir = dds_security_plugin_dir(&searched);
    if (dir.empty())
        throw std::runtime_error(
            "dds.security: Cyclone DDS Security plugins (libdds_security_auth.so, _ac.so, "
            "_crypto.so) not found in " +
            searched);
    return "<Security><Authentication>" +
           library(dir, "auth", "init_authentication", "finalize_authentication") +
           "<IdentityCertificate>" + file_uri(s.certificate) +
           "</IdentityCertificate><IdentityCA>" + file_uri(s.identity_ca) +
           "</IdentityCA><PrivateKey>" + file_uri(s.private_key) +
           "</PrivateKey></Authentication><AccessControl>" +
           library(dir, "ac", "init_access_control", "finalize_access_control") +
           "<PermissionsCA>" + file_uri(s.permissions_ca) + "</PermissionsCA><Governance>" +
           file_uri(s.governance) + "</Governance><Permissions>" + file_uri(s.permissions) +
           "</Permissions></AccessControl><Cryptographic>" +
           library(dir, "crypto", "init_crypto", "finalize_crypto") + "</Cryptographic></Security>";
}

}  // namespace ltm::runtime
