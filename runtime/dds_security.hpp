#pragma once
// DDS Security (Cyclone's authentication, access control and cryptography plugins) for a host's
// participant: the files of a launch config's `dds.security` block and their Cyclone XML.
// launch_configs/security/make_site_certs.sh makes the files of a site.
#include <string>

namespace ltm::runtime {

// Absolute paths (the launch config loader expands ${VAR}s and checks that each file exists).
struct DdsSecurity {
    std::string identity_ca;     // PEM certificate of the CA that signed every participant's
    std::string certificate;     // PEM certificate of this participant
    std::string private_key;     // PEM private key of this participant (unencrypted)
    std::string permissions_ca;  // PEM certificate of the CA that signed the two documents below
    std::string governance;      // signed (S/MIME) governance document of the site
    std::string permissions;     // signed (S/MIME) permissions document of this participant
    bool enabled() const { return !certificate.empty(); }
};

// The folder holding Cyclone's security plugins (libdds_security_auth.so, _ac, _crypto): next to
// the libddsc this process loaded, or in its `libddsc0debian/` subfolder (Debian's layout).
// "" when they are not there; `searched` then names the folders looked in.
std::string dds_security_plugin_dir(std::string* searched = nullptr);

// The <Security> element of the Cyclone XML for `security`, loading the plugins by absolute path
// (no LD_LIBRARY_PATH needed). Throws std::runtime_error (one line) when the plugins are missing.
std::string dds_security_xml(const DdsSecurity& security);

}  // namespace ltm::runtime
