# Sourced by deploy/containers.sh (its variables and log/die): installing podman and building the images.
# ---------------------------------------------------------------------------------------------------- install

install_packages() {
  # runc named explicitly: podman depends on "crun | runc", and crun fails on this kind of host's cgroups.
  # netavark: podman's network stack; iptables: netavark's firewall rules; aardvark-dns: compose's service names.
  local packages=(podman runc netavark aardvark-dns iptables debootstrap debian-archive-keyring podman-compose
    python3)
  local missing=() p
  for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$p")
    fi
  done
  if [ ${#missing[@]} -eq 0 ]; then
    return 0
  fi
  [ "$(id -u)" -eq 0 ] || die "missing packages ${missing[*]}: run as root to install them"
  log "installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" > /dev/null
}

# ------------------------------------------------------------------------------------------------------ build

image_name() { echo "localhost/swa-$1:latest"; }

# The programs the images carry, all present in --bin-dir (build, and containers.sh --dry-run).
require_binaries() {
  local b
  for b in swa_agent swa_sim swa_monitor swa_px4_bridge swa_batch; do
    [ -x "$bin_dir/$b" ] || die "$bin_dir/$b not found: build first (bash deploy/build.sh) or pass --bin-dir"
  done
}

build_images() {
  install_packages
  [ "$(id -u)" -eq 0 ] || die "build needs root (debootstrap, rootful podman)"
  require_binaries
  # Inside a container only SWA_TRANSPORT=network keeps shared memory out; binaries from before it would try
  # shared memory between containers and silently test something else.
  # The help captured first: `grep -q` stops reading at the match, and the rest of a help longer than one pipe write
  # would end the program with SIGPIPE (a failed pipeline under pipefail).
  local help
  help=$("$bin_dir/swa_sim" --help 2>&1) || die "$bin_dir/swa_sim --help failed: rebuild the project"
  grep -q SWA_TRANSPORT <<<"$help" || die "$bin_dir/swa_sim does not know SWA_TRANSPORT: rebuild the project"

  local base_args=(--engine podman --image "$base_image")
  [ "$rebuild_base" -eq 0 ] || base_args+=(--rebuild)
  timeout 600 bash "$here/build-base.sh" "${base_args[@]}" || die "base image not built"

  local context
  context=$(mktemp -d /var/tmp/swa-image-context.XXXXXX)
  temp_dirs+=("$context")
  mkdir -p "$context/bin" "$context/scenarios"
  # install -m: the modes in the image must not depend on how the checkout or the build set them.
  install -m 0755 "$bin_dir/swa_agent" "$bin_dir/swa_sim" "$bin_dir/swa_monitor" "$bin_dir/swa_px4_bridge" \
    "$bin_dir/swa_batch" "$here/swa-entrypoint" "$context/bin/"
  install -m 0644 "$root/idl/runtime/dds/profiles.xml" "$context/"
  install -m 0644 "$root"/deploy/scenarios/*.yaml "$context/scenarios/"

  local target start
  for target in agent sim monitor bridge batch; do
    start=$SECONDS
    # Host network for the build only: apt-get in the runtime stage must reach the Debian archive; the swarm
    # itself runs on its internal bridge.
    if ! timeout 600 podman build --network host --build-arg "BASE_IMAGE=$base_image" --target "$target" \
      -t "$(image_name "$target")" -f "$here/Dockerfile" "$context" > "$context/build-$target.log" 2>&1; then
      tail -n 40 "$context/build-$target.log" >&2
      die "image $target not built"
    fi
    log "image $(image_name "$target") ready ($((SECONDS - start)) s)"
  done
  rm -rf "$context"
}
