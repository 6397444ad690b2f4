#!/bin/sh
# `make run`: starts depthkeyd in the foreground on the simulated devices,
# after saying once how to look at what it produces.
bin=$1
config=config/depthkey.toml
snapshots=${TMPDIR:-/tmp}/depthkey-snapshots
cat <<MSG
depthkeyd is starting on simulated cameras (config: $config).
Look at its output from another terminal:
  $bin/depthkey-shmcat --frames 250 | ffmpeg -y -i - composite.mp4     # 10 s of the composite
  $bin/depthkey-shmcat --stream lecturer --frames 1 | ffmpeg -y -i - lecturer.png
  kill -USR1 \$(pidof depthkeyd)    # stage snapshots (PNG) into $snapshots
  kill -HUP \$(pidof depthkeyd)     # re-read $config
Status lines below; Ctrl-C stops it.
MSG
exec "$bin/depthkeyd" --config "$config" --snapshot-dir "$snapshots"
