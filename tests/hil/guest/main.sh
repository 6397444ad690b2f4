#!/bin/bash
# The HIL suite, run as root inside the VM by tests/hil/run.sh: loads the
# virtual devices (emulated SR-2 on dummy_hcd, vivid, gpio-sim), starts udev,
# checks each device on its own, then runs the real depthkeyd against them
# (daemon.sh; or the fault campaign, campaign.sh, when HIL_CAMPAIGN_FAULTS
# is set). HIL_BIN is the folder of the binaries under test.
set -u
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
: "${HIL_BIN:?HIL_BIN must name the folder of the binaries under test}"
: >"$HIL_RESULTS"
echo "hil: guest started at $(hil_uptime) s"

# --- devices ----------------------------------------------------------------
modprobe configfs && mount -t configfs configfs /sys/kernel/config
echo "hil: configfs at $(hil_uptime) s"
# udev before the devices appear: hotplug events reach libusb, and rules
# create /dev/v4l/by-id links. Triggering all devices would cost ~15 s.
/lib/systemd/systemd-udevd --daemon >"$HIL_LOGS/udevd.log" 2>&1
hil_check udev-running hil_wait 20 udevadm control --ping

# gpio-sim and dummy_hcd are this project's builds (tests/hil/kmod).
hil_check gpio-sim-module modprobe gpio-sim
# Two vivid instances: /dev/video0 the webcam, /dev/video1 the board's
# capture stick (board.backend = "v4l2").
hil_check vivid-module modprobe vivid n_devs=2 node_types=0x1,0x1 input_types=0x0,0x0
hil_check usb-gadget-modules modprobe -a libcomposite usb_f_fs dummy_hcd
# The virtual webcam's device, as README "Virtual webcam" sets it up on a box
# (built from Debian's v4l2loopback-dkms by tests/hil/kmod/v4l2loopback.sh).
WEBCAM_MISSING=""
if [ -f "$VM_RESULTS/v4l2loopback-missing" ]; then
	WEBCAM_MISSING=$(cat "$VM_RESULTS/v4l2loopback-missing")
elif ! out=$(modprobe v4l2loopback video_nr=10 card_label=depthkey exclusive_caps=1 2>&1); then
	WEBCAM_MISSING="modprobe v4l2loopback failed: $out"
elif ! hil_wait 10 test -c /dev/video10; then
	WEBCAM_MISSING="v4l2loopback loaded but /dev/video10 did not appear"
fi
[ -z "$WEBCAM_MISSING" ] && hil_pass v4l2loopback-module "/dev/video10 $(cat /sys/class/video4linux/video10/name)"

led_chip=$(gpio_sim_create)
hil_check gpio-sim-chip test -c "/dev/$led_chip"

# The spare line 7: driven by libgpiod's tool, read back from the simulator.
gpioset --mode=signal "$led_chip" 7=1 &
gpioset_pid=$!
hil_check gpio-sim-readback hil_wait 10 gpio_is 7 1
kill "$gpioset_pid"; wait "$gpioset_pid" 2>/dev/null

hil_check vivid-streams v4l2-ctl -d /dev/video0 --set-fmt-video=width=320,height=180,pixelformat=YUYV \
	--stream-mmap --stream-count=10
hil_check vivid-board-streams v4l2-ctl -d /dev/video1 --set-fmt-video=width=640,height=360,pixelformat=YUYV \
	--stream-mmap --stream-count=5

sr2_start
hil_check sr2-enumerates hil_wait 20 sr2_present
hil_check sr2-endpoints sh -c "lsusb -v -d 0852:0071 2>/dev/null | grep -c 'bEndpointAddress *0x\(88  EP 8 IN\|02  EP 2 OUT\)' | grep -qx 2"
hil_check sr2-udev-sees-it hil_wait 20 sh -c "udevadm info /dev/bus/usb/001/* | grep -q ID_MODEL_ID=0071"
hil_check sr2-frames-over-libusb "$HIL_BIN/depthkey-hil-sr2-probe" 3
hil_check sr2-output-mode-register grep -q 'register 0x02 = 0xc0' "$SR2_LOG"
sr2_cmd short 1
if out=$("$HIL_BIN/depthkey-hil-sr2-probe" 1 2>&1); then
	hil_fail sr2-short-frame "a short frame was read in full: $out"
else
	hil_pass sr2-short-frame "$(echo "$out" | head -n1)"
fi
sr2_cmd unplug
hil_check sr2-unplug hil_wait 20 sr2_absent
sr2_cmd replug
hil_check sr2-replug hil_wait 20 sr2_present

# --- the daemon on these devices --------------------------------------------
# The HIL suite's checks (daemon.sh), or with HIL_CAMPAIGN_FAULTS set the
# fault campaign instead (campaign.sh, `make hil-campaign`).
suite=daemon.sh
[ -z "${HIL_CAMPAIGN_FAULTS:-}" ] || suite=campaign.sh
if bash -n "$here/faults.sh" && bash -n "$here/$suite"; then
	. "$here/$suite"
else
	hil_fail daemon-suite "tests/hil/guest/$suite or faults.sh does not parse"
fi

# --- end ----------------------------------------------------------------------
echo quit >"$SR2_FIFO"
hil_wait 10 sh -c "! kill -0 $SR2_PID"
dmesg >"$HIL_LOGS/dmesg.log"
# run.sh counts a suite that did not get here (a script error) as failed.
echo "END" >>"$HIL_RESULTS"
! grep -q '^FAIL' "$HIL_RESULTS"
