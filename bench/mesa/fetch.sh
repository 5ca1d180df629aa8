#!/usr/bin/env bash
# Mesa 25.0.7 (llvmpipe) from Debian's bookworm-backports, unpacked into a
# private folder, without touching the system's Mesa or anything in /etc.
#
#   bash bench/mesa/fetch.sh [DIR]          # default DIR: target/mesa-25
#   eval "$(bash bench/mesa/fetch.sh)"      # also set the variables in this shell
#
# It downloads the .deb files with `apt-get download` through a private apt
# configuration (its own sources list, lists and cache under DIR/apt), unpacks
# them with `dpkg -x` into DIR/root, checks with EGL that GL_RENDERER says
# "llvmpipe" and GL_VERSION "Mesa 25.0.7", and prints on stdout the `export`
# lines that select it:
#
#   LD_LIBRARY_PATH                  the backported libgallium, libGLX/EGL_mesa, libgbm, libdrm, libwayland
#   LIBGL_DRIVERS_PATH               its dri/ folder (swrast_dri.so)
#   __EGL_VENDOR_LIBRARY_FILENAMES   its 50_mesa.json, pointing at its libEGL_mesa.so.0
#
# Progress goes to stderr. Rerunning reuses what is already unpacked.
# Needs: apt-get, dpkg, python3 (for the check), and Debian's libegl1 (glvnd).
set -euo pipefail
cd "$(dirname "$0")/../.."
dir=$(realpath -m "${1:-target/mesa-25}")
want=${MESA_VERSION:-25.0.7}
root="$dir/root"
lib="$root/usr/lib/x86_64-linux-gnu"
say() { printf '%s\n' "$*" >&2; }

if [ ! -f "$dir/.done-$want" ]; then
  mkdir -p "$dir/apt/parts.d" "$dir/apt/lists/partial" "$dir/apt/cache/archives/partial" "$dir/debs" "$root"
  cat >"$dir/apt/sources.list" <<SOURCES
deb [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian bookworm main
deb [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian bookworm-backports main
SOURCES
  : >"$dir/apt/empty.conf"
  apt_opts=(
    -o "Dir::Etc::SourceList=$dir/apt/sources.list"
    -o "Dir::Etc::SourceParts=$dir/apt/parts.d"
    -o "Dir::Etc::Preferences=$dir/apt/empty.conf"
    -o "Dir::Etc::PreferencesParts=$dir/apt/parts.d"
    -o "APT::Sandbox::User=root"
    -o "Dir::State::Lists=$dir/apt/lists"
    -o "Dir::State::Status=/var/lib/dpkg/status"
    -o "Dir::Cache=$dir/apt/cache"
    -o "APT::Get::List-Cleanup=0"
  )
  say "mesa: apt-get update (private lists in $dir/apt) ..."
  apt-get "${apt_opts[@]}" update -qq >&2
  # The backported Mesa and what it needs newer than bookworm's own: libdrm
  # 2.4.12x and libwayland 1.23 (it uses bookworm's LLVM 15, installed with
  # Debian's Mesa; Mesa 25 has no separate libglapi).
  pkgs=(libgl1-mesa-dri libegl-mesa0 libgbm1 mesa-libgallium libglx-mesa0
        libdrm2 libdrm-amdgpu1 libdrm-intel1 libdrm-common
        libwayland-server0 libwayland-client0)
  resolved=()
  for p in "${pkgs[@]}"; do
    v=$(apt-cache "${apt_opts[@]}" madison "$p" 2>/dev/null | awk -F'|' '{gsub(/ /,"",$2); gsub(/ /,"",$3); print $2" "$3}' \
        | sort -V -r | awk '{print $1; exit}')
    if [ -z "$v" ]; then say "mesa: $p not found, skipped"; continue; fi
    case "$p" in
      libgl1-mesa-dri|libegl-mesa0|libgbm1|mesa-libgallium|libglx-mesa0)
        v=$(apt-cache "${apt_opts[@]}" madison "$p" | awk -F'|' -v w="$want" '{gsub(/ /,"",$2); if (index($2, w)==1) {print $2; exit}}')
        [ -n "$v" ] || { say "mesa: no $p $want in bookworm-backports"; exit 1; } ;;
    esac
    resolved+=("$p=$v")
  done
  say "mesa: downloading ${resolved[*]}"
  (cd "$dir/debs" && apt-get "${apt_opts[@]}" download "${resolved[@]}" >&2)
  for deb in "$dir"/debs/*.deb; do dpkg -x "$deb" "$root"; done
  touch "$dir/.done-$want"
fi
# glvnd's vendor file, pointing at the private libEGL_mesa; written every
# time, so that a folder copied or moved elsewhere still points at itself.
cat >"$dir/50_mesa.json" <<JSON
{"file_format_version": "1.0.0", "ICD": {"library_path": "$lib/libEGL_mesa.so.0"}}
JSON

exports="export LD_LIBRARY_PATH=$lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}
export LIBGL_DRIVERS_PATH=$lib/dri
export __EGL_VENDOR_LIBRARY_FILENAMES=$dir/50_mesa.json
export EGL_PLATFORM=surfaceless"

# Check what a program then gets, through EGL (surfaceless, no display).
check=$(env -i PATH="$PATH" HOME="${HOME:-/root}" bash -c "$exports
python3 - <<'PY'
import ctypes, ctypes.util
egl = ctypes.CDLL('libEGL.so.1'); gl = ctypes.CDLL('libOpenGL.so.0')
egl.eglGetDisplay.restype = ctypes.c_void_p
egl.eglGetPlatformDisplayEXT = None
get = egl.eglGetProcAddress; get.restype = ctypes.c_void_p
EGL_PLATFORM_SURFACELESS_MESA = 0x31DD
gpd = ctypes.CFUNCTYPE(ctypes.c_void_p, ctypes.c_uint, ctypes.c_void_p, ctypes.c_void_p)(get(b'eglGetPlatformDisplayEXT'))
dpy = gpd(EGL_PLATFORM_SURFACELESS_MESA, None, None)
ma, mi = ctypes.c_int(), ctypes.c_int()
assert egl.eglInitialize(ctypes.c_void_p(dpy), ctypes.byref(ma), ctypes.byref(mi)), 'eglInitialize failed'
egl.eglBindAPI(0x30A2)
cfg = ctypes.c_void_p(); n = ctypes.c_int()
attrs = (ctypes.c_int * 3)(0x3040, 0x0008, 0x3038)
egl.eglChooseConfig(ctypes.c_void_p(dpy), attrs, ctypes.byref(cfg), 1, ctypes.byref(n))
egl.eglCreateContext.restype = ctypes.c_void_p
ctx = egl.eglCreateContext(ctypes.c_void_p(dpy), cfg, None, None)
assert ctx, 'eglCreateContext failed'
assert egl.eglMakeCurrent(ctypes.c_void_p(dpy), None, None, ctypes.c_void_p(ctx)), 'eglMakeCurrent failed'
gl.glGetString.restype = ctypes.c_char_p
print(gl.glGetString(0x1F01).decode(), '|', gl.glGetString(0x1F02).decode())
PY")
say "mesa: $check"
case "$check" in
  *llvmpipe*"Mesa $want"*) ;;
  *) say "mesa: expected llvmpipe and Mesa $want"; exit 1 ;;
esac
printf '%s\n' "$exports"
