#!/usr/bin/python3
# The DISPLAY program of the oracle's headless LinuxCNC configs (trt.ini, bridge.ini): no
# window, no operator. It takes the machine out of E-stop, turns it on, homes every joint
# (immediate homing: HOME_SEARCH_VEL = 0), then runs each line of moves.txt (in the config's
# directory, the oracle's work copy) as one MDI command and writes, for each, the joint
# positions LinuxCNC commands once the move is done to joints.txt:
#   <line number> <joint 0> <joint 1> ...        (repr() of the doubles)
#   <line number> ERROR <LinuxCNC's message>
# When it exits, the `linuxcnc` script shuts everything down.
import linuxcnc
import sys
import time

stat = linuxcnc.stat()
command = linuxcnc.command()
errors = linuxcnc.error_channel()


def wait_for(test, what, timeout=10.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        stat.poll()
        if test():
            return
        time.sleep(0.002)
    sys.exit(f"drive.py: timed out waiting for {what}")


def error_text():
    e = errors.poll()
    return e[1].strip() if e else None


wait_for(lambda: True, "the first status")
command.state(linuxcnc.STATE_ESTOP_RESET)
command.wait_complete()
command.state(linuxcnc.STATE_ON)
command.wait_complete()
wait_for(lambda: stat.task_state == linuxcnc.STATE_ON, "machine on")
joints = stat.joints
command.teleop_enable(0)
command.wait_complete()
command.home(-1)
command.wait_complete()
wait_for(lambda: all(stat.homed[:joints]), "homing")
command.mode(linuxcnc.MODE_MDI)
command.wait_complete()
wait_for(lambda: stat.task_mode == linuxcnc.MODE_MDI, "MDI mode")

with open("moves.txt") as f:
    moves = [line.strip() for line in f if line.strip()]
with open("joints.txt", "w") as out:
    for number, move in enumerate(moves, 1):
        command.mdi(move)
        command.wait_complete(10.0)
        wait_for(lambda: stat.interp_state == linuxcnc.INTERP_IDLE and stat.queue == 0
                 and stat.inpos, f"move {number} ({move})")
        text = error_text()
        if text:
            out.write(f"{number} ERROR {text}\n")
            continue
        time.sleep(0.005)  # a few servo cycles more: the commanded joints have settled
        stat.poll()
        values = stat.joint_position[:joints]
        out.write(f"{number} " + " ".join(repr(v) for v in values) + "\n")
        out.flush()
