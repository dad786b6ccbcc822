#!/usr/bin/env bash
# install_flightgear.sh: FlightGear 2020.3 from Debian for ./run flightgear, when it is missing (1.8 GB, about
# 3 minutes), and ImageMagick's import for the screenshots. Root; says how long it took.
set -euo pipefail
needed=()
[ -x /usr/games/fgfs ] || needed+=(flightgear)
command -v import >/dev/null || needed+=(imagemagick)
command -v Xvfb >/dev/null || needed+=(xvfb)
if [ ${#needed[@]} -eq 0 ]; then
  echo "install_flightgear: FlightGear $(dpkg-query -W -f '${Version}' flightgear 2>/dev/null || echo '?') is installed"
  exit 0
fi
if [ "$(id -u)" != 0 ]; then
  echo "install_flightgear: ${needed[*]} missing; installing needs root (apt-get install --no-install-recommends ${needed[*]})" >&2
  exit 1
fi
start=$SECONDS
echo "install_flightgear: apt-get install --no-install-recommends ${needed[*]} (FlightGear: 1.8 GB)"
apt-get update -qq
DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${needed[@]}" >/dev/null
echo "install_flightgear: installed in $((SECONDS - start)) s"
