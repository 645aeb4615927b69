#!/usr/bin/env python3
"""`fogpipe view` under Xvfb: B then quick Ctrl+S taps (press and release between two
frames, as a person taps on a few-frames-a-second software renderer) write
NAME.painted.ini. With GLFW's sticky keys the first read of a frame takes a latched press:
the camera read S and Ctrl before the brush did, and no tap ever saved (app/window_keys.h).
Keys are sent with XTest; skips (77) where xvfb-run's display or libXtst is missing.
Usage: window_ctrl_s_tap.py FOGPIPE (run under xvfb-run)."""
import ctypes, ctypes.util, os, shutil, subprocess, sys, tempfile, time

def main():
    if not os.environ.get("DISPLAY"):
        print("no display: skipped"); return 77
    try:
        x11 = ctypes.cdll.LoadLibrary("libX11.so.6")
        xtst = ctypes.cdll.LoadLibrary("libXtst.so.6")
    except OSError as e:
        print(f"no X11/XTest library ({e}): skipped"); return 77
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XKeysymToKeycode.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
    display = ctypes.c_void_p(x11.XOpenDisplay(None))
    def key(sym, down):
        xtst.XTestFakeKeyEvent(display, x11.XKeysymToKeycode(display, sym), down, 0)
        x11.XFlush(display)
    XK_b, XK_s, XK_Control_L = 0x62, 0x73, 0xFFE3
    folder = tempfile.mkdtemp(prefix="fogpipe-ctrl-s-")
    try:
        config = os.path.join(folder, "banks.ini")
        shutil.copy("configs/rbf_fog_banks.ini", config)
        view = subprocess.Popen([sys.argv[1], "view", config, "--size", "320x180"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(6)  # the window up and drawing
        key(XK_b, 1); key(XK_b, 0)  # the brush on
        time.sleep(2)
        painted = os.path.join(folder, "banks.painted.ini")
        for _ in range(3):  # taps: all four events between two frames
            key(XK_Control_L, 1); key(XK_s, 1); key(XK_s, 0); key(XK_Control_L, 0)
            time.sleep(1.5)
            if os.path.exists(painted):
                break
        view.terminate(); view.wait(10)
        if not os.path.exists(painted):
            print("FAIL: three quick Ctrl+S taps with the brush on wrote no banks.painted.ini")
            return 1
        print("a quick Ctrl+S tap wrote banks.painted.ini")
        return 0
    finally:
        shutil.rmtree(folder, ignore_errors=True)

sys.exit(main())
