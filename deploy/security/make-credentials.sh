#!/usr/bin/env bash
# DDS Security credentials for an SWA swarm: one CA, one identity per participant, the governance document and
# per-participant permissions, laid out as swa::dds::Participant expects them (idl/runtime/dds/include/swa/dds/deployment.h).
# Run with --help for the layout, the options and the overwrite rules.
set -euo pipefail

readonly PROG=${0##*/}
readonly MAX_DOMAIN=232   # highest DDS domain id whose RTPS ports fit in 16 bits with Fast DDS's default port mapping
readonly MAX_UAVS=10000   # swa_agent --id accepts 0..9999

usage() {
  cat <<EOF
$PROG: DDS Security credentials (CA, identities, governance, permissions) for an SWA swarm.

Usage: $PROG [options] DIR N

Creates in DIR, for the simulator, the monitor and N UAVs (swa_agent_0 .. swa_agent_<N-1>):
  ca.pem                      the CA certificate (identity CA and permissions CA): every participant needs it
  ca/key.pem                  the CA's private key (0600): keep it offline, never copy it to a drone
  governance.xml, .p7s        the domain governance, signed by the CA
  <name>/cert.pem, key.pem    the participant's identity (EC prime256v1), key 0600
  <name>/permissions.xml, .p7s  what it may publish and subscribe, signed by the CA
<name> is swa_sim, swa_monitor, swa_ground, swa_agent_<I> or (--bridges) swa_bridge_<I>. The .xml files are the unsigned
text, for reading only.

Governance (domains 0-$MAX_DOMAIN by default): only authenticated participants whose permissions grant the
domain may join; every topic's data and submessages are encrypted, and so is endpoint discovery and liveliness;
reading or writing a topic needs a permissions grant.
Permissions (default DENY, nothing else is allowed):
  swa_agent_<I>  reads swa/uav<I>/imu, swa/uav<I>/detections, swa/uav<I>/gnss, swa/uav<I>/sensors, swa/clock,
                 the ground's swa/swarm/mission, and a real detector's rt/uav<I>/detections (vision_msgs) or
                 rt/uav<I>/uvdar/measuredPoses (UVDAR);
                 writes swa/uav<I>/cmd_vel, swa/uav<I>/state (and swa/uav<I>/cmd_vel_stamped with --naming ros2)
  swa_sim        writes swa/uav*/imu, swa/uav*/detections, swa/uav*/gnss, swa/uav*/sensors, swa/truth,
                 swa/events, swa/clock, rt/uav*/detections, rt/uav*/uvdar/measuredPoses;
                 reads swa/uav*/cmd_vel; as every UAV's PX4 stand-in (vehicle.interface=px4) writes
                 rt/<P>*/fmu/out/vehicle_attitude, sensor_combined, vehicle_status(_v1), vehicle_command_ack,
                 vehicle_gps_position, vehicle_local_position(_v1) and reads
                 rt/<P>*/fmu/in/trajectory_setpoint, offboard_control_mode, vehicle_command; as every UAV's
                 ArduPilot stand-in (vehicle.interface=ardupilot) writes rt/ap/v*/imu/experimental/data,
                 status, navsat and the replies rr/ap/v*/arm_motorsReply, mode_switchReply, and reads
                 rt/ap/v*/cmd_vel and the requests rq/ap/v*/arm_motorsRequest, mode_switchRequest
  swa_monitor    reads swa/truth, swa/events, swa/uav*/state, and to record them (swa_monitor --record) swa/clock,
                 swa/uav*/imu, swa/uav*/detections, swa/uav*/gnss, swa/uav*/sensors, swa/uav*/cmd_vel,
                 swa/uav*/bridge_state; and the ground's swa/swarm/mission (it scores the run against it)
  swa_ground     the ground station (swa_mission): writes swa/swarm/mission, nothing else
  swa_bridge_<I> (only with --bridges) the autopilot bridge of UAV I (swa_px4_bridge, or a bridge of your own):
                 writes swa/uav<I>/imu, swa/uav<I>/detections, swa/uav<I>/gnss, swa/uav<I>/bridge_state and
                 rt/<P><I>/fmu/in/trajectory_setpoint, offboard_control_mode, vehicle_command;
                 reads swa/uav<I>/cmd_vel and rt/<P><I>/fmu/out/vehicle_attitude, sensor_combined, vehicle_status(_v1),
                 vehicle_command_ack, vehicle_gps_position, vehicle_local_position(_v1); for an ArduPilot
                 vehicle (namespace ap/v<I+1>) writes rt/ap/v<I+1>/cmd_vel and the requests
                 rq/ap/v<I+1>/arm_motorsRequest, mode_switchRequest, and reads rt/ap/v<I+1>/imu/experimental/data,
                 status, navsat and the replies rr/ap/v<I+1>/arm_motorsReply, mode_switchReply
<P> is the PX4 namespace prefix (--px4-prefix, default px4_: UAV I's PX4 runs uxrce_dds_client with -n px4_<I>).
(_v1): both names, so the same credentials serve every PX4 release (v1.16 and v1.17 version these topics).
With --naming ros2 every swa/... topic above is rt/[<NS>/]swa/... (SWA_NAMING=ros2, SWA_ROS_NAMESPACE=<NS>).

Options:
  --days D        validity of identities and permissions in days (default 365)
  --ca-days D     validity of a new CA in days (default 3650)
  --domains A-B   DDS domain ids covered by governance and permissions, A-B or one id (default 0-$MAX_DOMAIN)
  --org NAME      organisation in every subject, O=NAME (default SWA; letters, digits, space, . _ -)
  --bridges       also swa_bridge_0 .. swa_bridge_<N-1>, one identity per UAV's autopilot bridge
  --px4-prefix P  PX4 namespaces are P<I> (default px4_, as swa_px4_bridge and swa_sim assume)
  --naming N      swa (default) or ros2: the topic names of SWA_NAMING the swarm runs with
  --ros-namespace NS  with --naming ros2: the SWA_ROS_NAMESPACE the swarm runs with
  --reuse-ca      DIR already holds credentials: keep its CA (ca.pem, ca/key.pem) and issue everything else
                  anew (rotation: drones keep their ca.pem, get new cert/key/permissions and governance)
  --force         DIR already holds credentials: replace all of them, CA included (every participant then
                  needs the new ca.pem too)
  -h, --help      this text

Overwriting: without --reuse-ca or --force, DIR must not exist or be empty, so existing credentials are never
replaced by accident. With either flag the script replaces only the entries listed above (and removes
swa_agent_<I> / swa_bridge_<I> directories beyond the new N or without --bridges); other files in DIR are left
alone. Everything is first written to a
staging directory inside DIR and moved into place only once all of it was created and verified, so a failure
leaves DIR as it was.

Subjects are O=<org>, CN=<name>; each permissions document names its subject exactly as
'openssl x509 -noout -subject -nameopt RFC2253' prints it (CN=...,O=...), which is what Fast DDS compares.
Validity starts now (UTC); a drone whose clock is behind rejects the certificates until its clock catches up.

Example:
  $PROG creds 4 && swa_launch --secure creds --scenario deploy/scenarios/dropout_4.yaml

Exit status: 0 created; 1 failure (DIR unchanged); 2 bad arguments.
Needs: openssl (tested with OpenSSL 3.0, Debian 12).
EOF
}

die() {
  echo "$PROG: $*" >&2
  exit 1
}

usage_error() {
  echo "$PROG: $*" >&2
  echo "(see $PROG --help)" >&2
  exit 2
}

# True if $1 is a decimal integer within [$2, $3].
in_range() { [[ $1 =~ ^[0-9]{1,9}$ ]] && ((10#$1 >= $2 && 10#$1 <= $3)); }

# Globals set by parse_args.
DIR='' N='' DAYS=365 CA_DAYS=3650 DOMAIN_MIN=0 DOMAIN_MAX=$MAX_DOMAIN ORG=SWA MODE=new BRIDGES=false
PX4_PREFIX=px4_ NAMING=swa ROS_NS=''
# The DDS names of SWA's topics (idl/runtime/dds/include/swa/dds/naming.h): "swa/" or, in the ros2 naming, "rt/[NS/]swa/".
SWA_ROOT=swa/

parse_args() {
  local positional=()
  while (($#)); do
    case $1 in
      -h | --help)
        usage
        exit 0
        ;;
      --days | --ca-days | --domains | --org | --px4-prefix | --naming | --ros-namespace)
        (($# >= 2)) || usage_error "$1 needs a value"
        case $1 in
          --days) DAYS=$2 ;;
          --ca-days) CA_DAYS=$2 ;;
          --domains) parse_domains "$2" ;;
          --org) ORG=$2 ;;
          --px4-prefix) PX4_PREFIX=$2 ;;
          --naming) NAMING=$2 ;;
          --ros-namespace) ROS_NS=${2#/} ;;
        esac
        shift 2
        ;;
      --bridges)
        BRIDGES=true
        shift
        ;;
      --reuse-ca | --force)
        [[ $MODE == new ]] || usage_error "--reuse-ca and --force exclude each other"
        MODE=${1#--}
        shift
        ;;
      --)
        shift
        positional+=("$@")
        break
        ;;
      -*) usage_error "unknown option $1" ;;
      *)
        positional+=("$1")
        shift
        ;;
    esac
  done
  ((${#positional[@]} == 2)) || usage_error "expected DIR and N, got ${#positional[@]} argument(s)"
  DIR=${positional[0]}
  N=${positional[1]}
  [[ -n $DIR ]] || usage_error "DIR is empty"
  in_range "$N" 1 "$MAX_UAVS" || usage_error "N '$N' is not a UAV count 1..$MAX_UAVS"
  N=$((10#$N))
  in_range "$DAYS" 1 100000 || usage_error "--days '$DAYS' is not a number of days 1..100000"
  in_range "$CA_DAYS" 1 100000 || usage_error "--ca-days '$CA_DAYS' is not a number of days 1..100000"
  DAYS=$((10#$DAYS)) CA_DAYS=$((10#$CA_DAYS))
  # Subjects go into -subj and into XML unescaped: only characters that need no escaping in either.
  [[ $ORG =~ ^[A-Za-z0-9][A-Za-z0-9\ ._-]*$ ]] || usage_error "--org '$ORG': use letters, digits, space, . _ -"
  # ROS name tokens (what swa_px4_bridge --px4-namespace and SWA_ROS_NAMESPACE accept).
  [[ $PX4_PREFIX =~ ^[A-Za-z_][A-Za-z0-9_]*$ && $PX4_PREFIX != *__* ]] ||
    usage_error "--px4-prefix '$PX4_PREFIX': letters, digits and '_', not starting with a digit, no '__'"
  case $NAMING in
    swa) [[ -z $ROS_NS ]] || usage_error "--ros-namespace needs --naming ros2" ;;
    ros2)
      if [[ -n $ROS_NS ]]; then
        [[ $ROS_NS =~ ^[A-Za-z_][A-Za-z0-9_]*(/[A-Za-z_][A-Za-z0-9_]*)*$ && $ROS_NS != *__* ]] ||
          usage_error "--ros-namespace '$ROS_NS' is not a ROS namespace (tokens of letters, digits, '_' and '/')"
        SWA_ROOT=rt/$ROS_NS/swa/
      else
        SWA_ROOT=rt/swa/
      fi
      ;;
    *) usage_error "--naming '$NAMING' is not swa or ros2" ;;
  esac
}

parse_domains() {
  local a b
  if [[ $1 =~ ^([0-9]+)-([0-9]+)$ ]]; then
    a=${BASH_REMATCH[1]} b=${BASH_REMATCH[2]}
  elif [[ $1 =~ ^[0-9]+$ ]]; then
    a=$1 b=$1
  else
    usage_error "--domains '$1' is not A-B or one domain id"
  fi
  if ! in_range "$a" 0 "$MAX_DOMAIN" || ! in_range "$b" "$((10#$a))" "$MAX_DOMAIN"; then
    usage_error "--domains '$1': need 0 <= A <= B <= $MAX_DOMAIN"
  fi
  DOMAIN_MIN=$((10#$a)) DOMAIN_MAX=$((10#$b))
}

STAGE='' CREATED_DIR=false

# On any exit: the staging directory goes; so does DIR if this run created it and failed before filling it.
cleanup() {
  if [[ -n $STAGE ]]; then rm -rf -- "$STAGE"; fi
  if $CREATED_DIR && [[ -d $DIR && -z $(ls -A "$DIR") ]]; then rmdir -- "$DIR"; fi
}

participants() {
  local i
  echo swa_sim
  echo swa_monitor
  echo swa_ground
  for ((i = 0; i < N; ++i)); do echo "swa_agent_$i"; done
  if $BRIDGES; then
    for ((i = 0; i < N; ++i)); do echo "swa_bridge_$i"; done
  fi
}

# Refuses to touch credentials it was not told to replace (see --help, Overwriting).
check_target() {
  if [[ -e $DIR && ! -d $DIR ]]; then die "$DIR exists and is not a directory"; fi
  local has_credentials=false
  [[ -e $DIR/ca.pem ]] && has_credentials=true
  case $MODE in
    new)
      if [[ -d $DIR ]] && [[ -n $(ls -A "$DIR") ]]; then
        if $has_credentials; then
          die "$DIR already holds credentials; --reuse-ca re-issues them with the same CA, --force replaces all"
        fi
        die "$DIR is not empty and holds no SWA credentials; choose an empty or new directory"
      fi
      ;;
    reuse-ca)
      [[ -r $DIR/ca.pem && -r $DIR/ca/key.pem ]] ||
        die "--reuse-ca: $DIR/ca.pem and $DIR/ca/key.pem must exist (the CA to keep)"
      openssl x509 -in "$DIR/ca.pem" -noout -checkend 0 >/dev/null ||
        die "--reuse-ca: the CA in $DIR/ca.pem has expired; use --force for a new CA"
      ;;
    force) ;;
  esac
}

# Extensions that OpenSSL's strict chain verification (X509_V_FLAG_X509_STRICT) expects of a CA and of its
# leaves: critical basicConstraints, key identifiers. digitalSignature on the CA because it also signs the
# governance and permissions documents (S/MIME).
write_openssl_config() {
  cat >"$1" <<'EOF'
[ req ]
distinguished_name = req_dn
prompt = no
[ req_dn ]
[ ca_ext ]
basicConstraints = critical, CA:TRUE
keyUsage = critical, keyCertSign, cRLSign, digitalSignature
subjectKeyIdentifier = hash
authorityKeyIdentifier = keyid:always
[ identity_ext ]
basicConstraints = critical, CA:FALSE
keyUsage = critical, digitalSignature
subjectKeyIdentifier = hash
authorityKeyIdentifier = keyid, issuer
EOF
}

new_key() {
  (umask 077 && openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:prime256v1 -out "$1" 2>/dev/null)
  chmod 0600 "$1"
}

random_serial() { echo "0x$(openssl rand -hex 16)"; }

make_ca() {
  local stage=$1 cnf=$2
  mkdir -p "$stage/ca"
  chmod 0700 "$stage/ca"
  new_key "$stage/ca/key.pem"
  openssl req -config "$cnf" -x509 -new -key "$stage/ca/key.pem" -sha256 -days "$CA_DAYS" \
    -set_serial "$(random_serial)" -subj "/O=$ORG/CN=$ORG DDS CA" -extensions ca_ext -out "$stage/ca.pem"
}

# Writes <name>/cert.pem and key.pem in $stage, signed by the CA files given.
make_identity() {
  local stage=$1 cnf=$2 ca_cert=$3 ca_key=$4 name=$5
  local dir=$stage/$name
  mkdir -p "$dir"
  new_key "$dir/key.pem"
  openssl req -config "$cnf" -new -key "$dir/key.pem" -subj "/O=$ORG/CN=$name" -out "$stage/$name.csr"
  openssl x509 -req -in "$stage/$name.csr" -CA "$ca_cert" -CAkey "$ca_key" -set_serial "$(random_serial)" \
    -days "$DAYS" -sha256 -extfile "$cnf" -extensions identity_ext -out "$dir/cert.pem" 2>/dev/null
  rm -f "$stage/$name.csr"
}

# The subject exactly as Fast DDS's access control compares it with <subject_name> (RFC 2253 order: CN first).
rfc2253_subject() {
  local s
  s=$(openssl x509 -in "$1" -noout -subject -nameopt RFC2253)
  echo "${s#subject=}"
}

# The governance and permissions documents (documents.sh: what each role may publish and subscribe).
# shellcheck source=documents.sh
source "$(dirname "${BASH_SOURCE[0]}")/documents.sh"

sign() {
  local ca_cert=$1 ca_key=$2 in=$3 out=$4
  openssl smime -sign -text -in "$in" -out "$out" -signer "$ca_cert" -inkey "$ca_key"
}

# Everything checked as the participants will check it, before anything is moved into DIR.
verify_stage() {
  local stage=$1 ca_cert=$2 name subject doc
  for doc in "$stage/governance.p7s" "$stage"/swa_*/permissions.p7s; do
    openssl smime -verify -text -in "$doc" -CAfile "$ca_cert" -out /dev/null 2>/dev/null ||
      die "internal error: $doc does not verify against $ca_cert"
  done
  while read -r name; do
    openssl verify -x509_strict -CAfile "$ca_cert" "$stage/$name/cert.pem" >/dev/null ||
      die "internal error: $name/cert.pem does not verify against $ca_cert"
    subject=$(rfc2253_subject "$stage/$name/cert.pem")
    grep -qF "<subject_name>$subject</subject_name>" "$stage/$name/permissions.xml" ||
      die "internal error: $name/permissions.xml does not name subject $subject"
  done < <(participants)
}

# Replaces DIR's entries by the staged ones, one rename each (staging is inside DIR: same file system).
install_stage() {
  local stage=$1 entry old
  for old in "$DIR"/swa_agent_* "$DIR"/swa_bridge_*; do
    if [[ -e $old && ! -e $stage/${old##*/} ]]; then rm -rf -- "$old"; fi
  done
  for entry in "$stage"/*; do
    old=$DIR/${entry##*/}
    if [[ -e $old ]]; then rm -rf -- "$old"; fi
    mv -- "$entry" "$old"
  done
}

main() {
  parse_args "$@"
  command -v openssl >/dev/null || die "openssl not found (apt-get install openssl)"
  check_target
  if [[ ! -d $DIR ]]; then
    mkdir -p "$DIR"
    CREATED_DIR=true
  fi
  STAGE=$(mktemp -d "$DIR/.staging.XXXXXX")
  trap cleanup EXIT

  local stage=$STAGE
  local cnf=$stage/openssl.cnf
  write_openssl_config "$cnf"

  local ca_cert ca_key
  if [[ $MODE == reuse-ca ]]; then
    ca_cert=$DIR/ca.pem ca_key=$DIR/ca/key.pem
  else
    make_ca "$stage" "$cnf"
    ca_cert=$stage/ca.pem ca_key=$stage/ca/key.pem
  fi

  # Fast DDS reads these with mktime(), i.e. as local time; UTC is what a drone's clock normally runs on.
  local not_before not_after
  not_before=$(date -u +%Y-%m-%dT%H:%M:%S)
  not_after=$(date -u -d "+$DAYS days" +%Y-%m-%dT%H:%M:%S)

  governance_xml >"$stage/governance.xml"
  sign "$ca_cert" "$ca_key" "$stage/governance.xml" "$stage/governance.p7s"

  local name subject
  while read -r name; do
    make_identity "$stage" "$cnf" "$ca_cert" "$ca_key" "$name"
    subject=$(rfc2253_subject "$stage/$name/cert.pem")
    permissions_xml "$name" "$subject" "$not_before" "$not_after" >"$stage/$name/permissions.xml"
    sign "$ca_cert" "$ca_key" "$stage/$name/permissions.xml" "$stage/$name/permissions.p7s"
  done < <(participants)
  rm -f "$cnf"

  verify_stage "$stage" "$ca_cert"
  install_stage "$stage"

  local what="new CA"
  [[ $MODE == reuse-ca ]] && what="CA kept"
  echo "$PROG: $DIR: $what, governance for domains $DOMAIN_MIN-$DOMAIN_MAX, swa_sim, swa_monitor, swa_ground," \
    "swa_agent_0..$((N - 1))$($BRIDGES && echo ", swa_bridge_0..$((N - 1))"), $NAMING naming;" \
    "identities and permissions valid until $not_after UTC"
}

main "$@"
