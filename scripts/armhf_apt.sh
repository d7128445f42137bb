# Sourced by scripts/armhf_sysroot.sh and scripts/ci_guest.sh: a private apt configuration for
# Debian 12 packages of a foreign architecture in DIR (sources, package lists, cache, an empty
# dpkg status), so that apt-get download works without `dpkg --add-architecture` and without
# touching the host's dpkg.
# armhf_apt_setup DIR [ARCH]: creates DIR's folders and sets the array `apt_opts` for
# apt-get/apt-cache. ARCH is a Debian architecture, armhf by default (arm64 for the 64-bit ARM
# build); one DIR holds one architecture's lists.
armhf_apt_setup() {
  local dir=$1 arch=${2:-armhf}
  mkdir -p "$dir"/{etc/sources.list.d,etc/preferences.d,state/lists/partial} "$dir"/cache/archives/partial
  : >"$dir/state/status"  # an empty dpkg database: nothing counts as installed
  local keyring=/usr/share/keyrings/debian-archive-keyring.gpg
  # (No bookworm-security: these packages only feed tests; the point release's are enough.)
  cat >"$dir/etc/sources.list" <<EOS
deb [arch=$arch signed-by=$keyring] http://deb.debian.org/debian bookworm main
deb [arch=$arch signed-by=$keyring] http://deb.debian.org/debian bookworm-updates main
EOS
  apt_opts=(
    -o APT::Architecture="$arch" -o APT::Architectures::="$arch"
    -o Dir::State="$dir/state" -o Dir::State::status="$dir/state/status"
    -o Dir::Cache="$dir/cache"
    -o Dir::Etc::SourceList="$dir/etc/sources.list"
    -o Dir::Etc::SourceParts="$dir/etc/sources.list.d"
    -o Dir::Etc::Preferences="$dir/etc/preferences"
    -o Dir::Etc::PreferencesParts="$dir/etc/preferences.d"
    -o Debug::NoLocking=1
    # Downloads go to folders this user owns; as root, do not hand them to the _apt user.
    -o APT::Sandbox::User="$(id -un)"
  )
}
