#!/usr/bin/env bash
# make_site_certs.sh [--site NAME] [--days N] [--domains MIN-MAX] OUT_DIR ROBOT [ROBOT...]
# The DDS Security files of one site (Cyclone DDS authentication, access control, encryption):
#   OUT_DIR/identity_ca.{pem,key}      signs every participant's certificate
#   OUT_DIR/permissions_ca.{pem,key}   signs the governance and every permissions document
#   OUT_DIR/governance.{xml,p7s}       discovery, liveliness and data of every topic encrypted
#   OUT_DIR/NAME/{cert,key}.pem        identity of base_station and of each ROBOT
#   OUT_DIR/NAME/permissions.{xml,p7s} base_station may publish and subscribe every topic; a
#                                      robot only its own namespace's (rt/ROBOT/*: run it with
#                                      --set namespace=/ROBOT), so a robot cannot read or forge
#                                      another robot's data
# Idempotent: existing keys and certificates are kept (a robot added later joins the same site);
# documents are signed again only when missing or older than the permissions CA.
set -euo pipefail
SITE=ltm; DAYS=3650; DOMAINS=0-230
usage() {
    echo "Makes the DDS Security certificates, keys and signed documents of a site"
    printf 'Usage: make_site_certs.sh [OPTIONS] OUT_DIR ROBOT [ROBOT...]\n\nOptions:\n'
    printf '  %-24s%s\n' "-h,--help" "Print this help message and exit" \
        "--site NAME=$SITE" "organisation (O=) of every certificate" \
        "--days UINT=$DAYS" "validity of certificates and permissions" \
        "--domains MIN-MAX=$DOMAINS" "DDS domains the permissions allow"
}
# One line, exit code 2 (usage) or 1 (openssl failed), as every ltm tool.
fail() { echo "make_site_certs.sh: $*" >&2; exit 2; }
name_ok() { [[ "$1" =~ ^[A-Za-z0-9_.-]+$ ]]; }
ARGS=()
while [ $# -gt 0 ]; do
    case "$1" in
        -h|--help) usage; exit 0 ;;
        --site|--days|--domains)
            [ $# -ge 2 ] || fail "$1: needs a value"
            case "$1" in
                --site) name_ok "$2" || fail "--site: expected letters, digits, _ . -, got '$2'"
                        SITE="$2" ;;
                --days) [[ "$2" =~ ^[1-9][0-9]*$ ]] || fail "--days: expected a positive integer, got '$2'"
                        DAYS="$2" ;;
                --domains) [[ "$2" =~ ^([0-9]+)-([0-9]+)$ ]] && [ "${BASH_REMATCH[1]}" -le "${BASH_REMATCH[2]}" ] \
                               && [ "${BASH_REMATCH[2]}" -le 230 ] || fail "--domains: expected MIN-MAX within 0-230 (the access control plugin's limit), got '$2'"
                           DOMAINS="$2" ;;
            esac
            shift 2 ;;
        -*) fail "$1: unknown option" ;;
        *) ARGS+=("$1"); shift ;;
    esac
done
[ ${#ARGS[@]} -ge 2 ] || fail "expected OUT_DIR and at least one ROBOT name (--help)"
command -v openssl >/dev/null || fail "openssl not found (apt-get install openssl)"
OUT="${ARGS[0]}"
NAMES=(base_station "${ARGS[@]:1}")
declare -A seen
for n in "${NAMES[@]}"; do
    name_ok "$n" || fail "robot name '$n': expected letters, digits, _ . -"
    [ -z "${seen[$n]:-}" ] || fail "participant '$n' given twice (base_station is always made)"
    seen[$n]=1
done
mkdir -p "$OUT" 2>/dev/null || fail "cannot create $OUT"
[ -w "$OUT" ] || fail "$OUT: not writable"
LOG="$OUT/.openssl.log"
# Runs openssl; on failure prints one line naming the step (details in OUT_DIR/.openssl.log).
ossl() {
    local what="$1"; shift
    openssl "$@" >>"$LOG" 2>&1 || { echo "make_site_certs.sh: openssl failed: $what (see $LOG)" >&2; exit 1; }
}
umask 077  # private keys readable by their owner only
DMIN="${DOMAINS%-*}"; DMAX="${DOMAINS#*-}"

# A self-signed CA (EC P-256: what Cyclone's authentication plugin accepts besides RSA-2048).
make_ca() {
    local base="$OUT/$1" cn="$2"
    [ -s "$base.pem" ] && [ -s "$base.key" ] && return 0
    ossl "$1 key" genpkey -algorithm EC -pkeyopt ec_paramgen_curve:P-256 -out "$base.key"
    ossl "$1 certificate" req -x509 -new -key "$base.key" -sha256 -days "$DAYS" \
        -subj "/O=$SITE/CN=$cn" -out "$base.pem"
}
make_ca identity_ca "$SITE identity CA"
make_ca permissions_ca "$SITE permissions CA"

# Signs XML document $1 with the permissions CA into $2 (S/MIME, as DDS Security requires).
sign() {
    if [ -s "$2" ] && [ "$2" -nt "$1" ] && [ "$2" -nt "$OUT/permissions_ca.pem" ]; then return 0; fi
    ossl "signing $1" smime -sign -in "$1" -text -out "$2" \
        -signer "$OUT/permissions_ca.pem" -inkey "$OUT/permissions_ca.key"
}
# Writes $2 to file $1 only when it changed (keeps the signature's timestamp check meaningful).
write_if_changed() {
    if [ -f "$1" ] && [ "$(cat "$1")" = "$2" ]; then return 0; fi
    printf '%s\n' "$2" > "$1"
}
XSD=http://www.omg.org/spec/DDS-SECURITY/20170901
DOMAIN_XML="<domains><id_range><min>$DMIN</min><max>$DMAX</max></id_range></domains>"

# Governance: only authenticated participants join; discovery, liveliness, metadata and data of
# every topic (ltm's rt/* and any other) encrypted, reads and writes checked against permissions.
topic_rule() {
    cat <<XML
      <topic_rule>
        <topic_expression>$1</topic_expression>
        <enable_discovery_protection>true</enable_discovery_protection>
        <enable_liveliness_protection>true</enable_liveliness_protection>
        <enable_read_access_control>true</enable_read_access_control>
        <enable_write_access_control>true</enable_write_access_control>
        <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
        <data_protection_kind>ENCRYPT</data_protection_kind>
      </topic_rule>
XML
}
write_if_changed "$OUT/governance.xml" "$(cat <<XML
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="$XSD/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      $DOMAIN_XML
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
$(topic_rule 'rt/*')
$(topic_rule '*')
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
XML
)"
sign "$OUT/governance.xml" "$OUT/governance.p7s"

NOT_BEFORE=$(date -u +%Y-%m-%dT%H:%M:%S -d '-1 day')
for n in "${NAMES[@]}"; do
    dir="$OUT/$n"
    mkdir -p "$dir"
    subject="/O=$SITE/CN=$n"
    if ! [ -s "$dir/cert.pem" ] || ! [ -s "$dir/key.pem" ] \
        || [ "$OUT/identity_ca.pem" -nt "$dir/cert.pem" ]; then
        ossl "$n key" genpkey -algorithm EC -pkeyopt ec_paramgen_curve:P-256 -out "$dir/key.pem"
        ossl "$n request" req -new -key "$dir/key.pem" -subj "$subject" -out "$dir/cert.csr"
        ossl "$n certificate" x509 -req -in "$dir/cert.csr" -CA "$OUT/identity_ca.pem" \
            -CAkey "$OUT/identity_ca.key" -CAcreateserial -days "$DAYS" -sha256 -out "$dir/cert.pem"
        rm -f "$dir/cert.csr"
    fi
    # The grant names the certificate's subject; validity from the certificate's own dates.
    not_after=$(date -u +%Y-%m-%dT%H:%M:%S -d "$(openssl x509 -in "$dir/cert.pem" -noout -enddate | cut -d= -f2)")
    old_before=$(sed -n 's:.*<not_before>\(.*\)</not_before>.*:\1:p' "$dir/permissions.xml" 2>/dev/null || true)
    topics='*'; [ "$n" = base_station ] || topics="rt/$n/*"
    write_if_changed "$dir/permissions.xml" "$(cat <<XML
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="$XSD/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="$n">
      <subject_name>CN=$n,O=$SITE</subject_name>
      <validity><not_before>${old_before:-$NOT_BEFORE}</not_before><not_after>$not_after</not_after></validity>
      <allow_rule>
        $DOMAIN_XML
        <publish><topics><topic>$topics</topic></topics></publish>
        <subscribe><topics><topic>$topics</topic></topics></subscribe>
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
XML
)"
    sign "$dir/permissions.xml" "$dir/permissions.p7s"
done
rm -f "$LOG"
echo "site '$SITE' in $OUT: identity and permissions CA, governance, ${NAMES[*]}"
