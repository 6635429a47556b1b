#!/usr/bin/env python3
"""Writes the demo traces for config/kiosk/demo.toml: a ~41 s walk on the first floor of the EnergyPlus house.

Start in hall 5642 at world (-0.585, 0.5), floor z 2.8, facing south (heading -90 deg in demo.toml), then:
south through the door of 5627 (door x -0.99..-0.18 at y -2.98: aim at its centre x -0.585) into 5627;
turn back north through the same door, up the hall to y 4.0; west through the open passage into 5634
(x -1.13, y 2.19..5.78: centre y ~3.99); back east; south down the hall to y -2.2; west to x -1.885; south
through the door of 5618 (x -2.28..-1.49 at y -2.98) into 5618. Turns happen standing still, on the
treadmill's steering. The head sways with each step, looks and leans around while the walker stands, and
glances aside once while walking; demo.toml shows it in screen mode (head position moves the eye behind the
fixed screen, head yaw never turns the walk), so the path is exact.
Run from this folder: python3 make_demo_traces.py
"""
import math

SPEED = 1.0  # m/s, an easy walking pace
RATE = 10    # samples per second

# (kind, value): ("walk", metres) at SPEED; ("turn", degrees, + = left) over 1.5 s; ("look", seconds)
PLAN = [
    ("look", 0.5),
    ("walk", 4.7),    # hall -> 5627 through its door, y 0.5 -> -4.2
    ("look", 1.5),
    ("turn", 180),    # face north
    ("walk", 8.2),    # back through the door and up the hall to y 4.0
    ("turn", 90),     # face west
    ("walk", 2.615),  # through the open passage into 5634, x -0.585 -> -3.2
    ("look", 1.5),
    ("turn", 180),    # face east
    ("walk", 2.615),  # back into the hall
    ("turn", -90),    # face south
    ("walk", 6.2),    # down the hall to y -2.2
    ("turn", -90),    # face west
    ("walk", 1.3),    # x -0.585 -> -1.885, in front of 5618's door
    ("turn", 90),     # face south
    ("walk", 2.0),    # through the door into 5618, y -2.2 -> -4.2
    ("look", 2.0),
]
TURN_SECONDS = 1.5


def head_sample(time, segments):
    """(time, yaw_deg, pitch_deg, x_m, y_m, z_m): the head relative to the body, tracker frame."""
    yaw, pitch, x, z = 0.0, -5.0, 0.0, 0.0
    for start, end, kind in segments:
        if not start <= time <= end:
            continue
        phase = (time - start) / (end - start)
        if kind == "look":  # look left, right and up, leaning the way it looks (a window shows more then)
            yaw = 35.0 * math.sin(2 * math.pi * phase)
            pitch = -5.0 + 15.0 * math.sin(math.pi * phase)
            x = -0.08 * math.sin(2 * math.pi * phase)
        else:  # walking: sway at half the step rate, bob at the step rate, one glance aside mid-leg
            x = 0.03 * math.sin(2 * math.pi * 0.9 * time)
            z = 0.015 * math.sin(2 * math.pi * 1.8 * time)
            if end - start > 6.0 and 0.4 < phase < 0.55:
                yaw = 25.0 * math.sin(math.pi * (phase - 0.4) / 0.15)
    return (time, yaw, pitch, x, 0.0, z)


def main():
    t = 0.0
    steering = 0.0
    tread = [(0.0, 0.0, 0.0)]      # time, speed, steering_deg
    segments = []                  # (start, end, kind) of the plan, for the head trace
    walks = []                     # start times of the walk legs, for the dimmer cues
    for kind, value in PLAN:
        if kind == "walk":
            walks.append(t)
            tread.append((t, SPEED, steering))
            segments.append((t, t + value / SPEED, "walk"))
            t += value / SPEED
            tread.append((t, 0.0, steering))
        elif kind == "turn":
            steps = int(TURN_SECONDS * RATE)
            for i in range(1, steps + 1):
                tread.append((t + i / RATE, 0.0, steering + value * i / steps))
            steering += value
            t += TURN_SECONDS + 1.0 / RATE
        else:  # look left, right, up, and back while standing
            segments.append((t, t + value, "look"))
            t += value + 1.0 / RATE
    end = t
    head = [head_sample(i / RATE, segments) for i in range(int(end * RATE) + 1)]
    # Dimmers: hall 5642 dims down and back, each room fades up as the walker heads for it.
    channels = ["5642", "5627", "5634", "5618"]
    def level(ch, time):
        ramp = lambda a, b: min(1.0, max(0.0, (time - a) / (b - a)))
        if ch == 0:  # hall: dims while the walker is in 5627, back up on the way to 5634
            return 1.0 - 0.7 * ramp(walks[0] + 3, walks[0] + 5) + 0.7 * ramp(walks[1] + 3, walks[1] + 6)
        if ch == 1:  # 5627: fades up as the walker approaches its door
            return 0.1 + 0.9 * ramp(walks[0], walks[0] + 3)
        if ch == 2:  # 5634
            return 0.1 + 0.9 * ramp(walks[2] - 2, walks[2] + 1)
        return 0.1 + 0.9 * ramp(walks[5] - 2, walks[5] + 1)  # 5618
    dimmers = [(i / 2, [level(c, i / 2) for c in range(len(channels))]) for i in range(int(end * 2) + 1)]

    def fmt(x):
        x = 0.0 if abs(x) < 5e-4 else x  # no "-0"
        return f"{x:.3f}".rstrip("0").rstrip(".") if "." in f"{x:.3f}" else str(x)
    # Collapse repeated times (a turn ending where the next walk starts): keep the last sample.
    def dedupe(rows):
        out = []
        for r in rows:
            if out and abs(out[-1][0] - r[0]) < 1e-9:
                out[-1] = r
            else:
                out.append(r)
        return out
    with open("demo_treadmill.csv", "w") as f:
        f.write("# generated by make_demo_traces.py: belt speed m/s, steering degrees (+ = left)\n")
        f.write("time,speed,steering_deg\n")
        for r in dedupe(tread):
            f.write(",".join(fmt(v) for v in r) + "\n")
    with open("demo_head.csv", "w") as f:
        f.write("# generated by make_demo_traces.py: head yaw/pitch in degrees relative to the body, position"
                " in metres from rest (x right, y forward, z up)\n")
        f.write("time,yaw_deg,pitch_deg,x_m,y_m,z_m\n")
        for r in dedupe(head):
            f.write(",".join(fmt(v) for v in r) + "\n")
    with open("demo_dimmers.csv", "w") as f:
        f.write("# generated by make_demo_traces.py: ch0..ch3 -> circuits " + ", ".join(channels) + "\n")
        f.write("time," + ",".join(f"ch{i}" for i in range(len(channels))) + "\n")
        for time, levels in dimmers:
            f.write(fmt(time) + "," + ",".join(fmt(v) for v in levels) + "\n")
    print(f"walk ends at t = {end:.2f} s")


if __name__ == "__main__":
    main()
