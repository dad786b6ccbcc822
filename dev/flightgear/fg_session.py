"""One FlightGear run for ./run flightgear (flightgear_check.py): Xvfb, fgfs with the cheapest settings,
its property server, its view read back through it frame by frame, screenshots, and an end that always comes.

FlightGear 2020.3 (Debian 12) under Xvfb with Mesa's software renderer: `LIBGL_ALWAYS_SOFTWARE=1`; without a
D-Bus session fgfs aborts unless `DBUS_FATAL_WARNINGS=0`; an error opens a dialog that waits forever, so
every wait here has a limit, and a failure takes a screenshot first. fgfs finds hkf's protocol file through
`--data` (DIR/Protocol/hkf.xml), so nothing is written into FlightGear's own folders. The property server
answers once a rendered frame, every request that came in since: six `get`s sent at once come back together.
"""
import os
import signal
import socket
import subprocess
import threading
import time

FGFS = "/usr/games/fgfs"
INPUT_PORT = 5550      # hkf's generic input (hkf-opentrack --flightgear's default port)
PROPS_PORT = 5401      # the property server
VIEW = "/sim/current-view"
VIEW_VALUES = ("heading-offset-deg", "pitch-offset-deg", "roll-offset-deg", "x-offset-m", "y-offset-m", "z-offset-m")
CHEAPEST = ["--compositor=Compositor/low-spec", "--disable-sound", "--disable-ai-traffic", "--disable-ai-models",
            "--disable-clouds", "--disable-clouds3d", "--disable-terrasync", "--disable-real-weather-fetch",
            "--disable-random-objects", "--disable-random-buildings", "--fog-fastest", "--timeofday=noon",
            "--disable-hud", "--geometry=800x600",
            # No terrain drawn: with no scenery FlightGear draws ocean tiles, and at some views (heading 0.39,
            # pitch -2.61 after 23.98, -2.62 every time) Mesa's software renderer takes 10 s over one frame of them.
            "--prop:bool:/sim/rendering/draw-mask/terrain=false"]


class FlightGearError(Exception):
    """FlightGear did not start, stopped answering, or exited: the message says which."""


def free_display():
    """A display number no X server uses."""
    for n in range(77, 200):
        if not os.path.exists(f"/tmp/.X11-unix/X{n}") and not os.path.exists(f"/tmp/.X{n}-lock"):
            return n
    raise FlightGearError("no free X display number in 77-199")


class Session:
    """Xvfb and fgfs for one aircraft; `with Session(...) as fg:` ends them, pass or fail."""

    def __init__(self, out, aircraft, data_dirs, log, max_fps=None):
        self.out, self.aircraft, self.data_dirs, self.log = out, aircraft, data_dirs, log
        self.max_fps = max_fps  # FlightGear's own frame-rate throttle: a slower machine's FlightGear
        self.display = free_display()
        self.xvfb = self.fgfs = None
        self.props = self.props_file = None
        self.reader = None
        self.samples = []  # (answer s, {property: value}) from the reader's requests, a frame each
        self.reading = False
        self.home = os.path.join(out, "fg-home")  # FlightGear's cache (navdata), kept between runs
        self.fg_log = os.path.join(out, f"fgfs-{aircraft}.log")

    def __enter__(self):
        os.makedirs(self.home, exist_ok=True)
        env = dict(os.environ, DISPLAY=f":{self.display}", LIBGL_ALWAYS_SOFTWARE="1", DBUS_FATAL_WARNINGS="0",
                   FG_HOME=self.home)
        self.xvfb = subprocess.Popen(["Xvfb", f":{self.display}", "-screen", "0", "800x600x24", "-nolisten", "tcp"],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(1.0)
        scenery = os.path.join(self.out, "no-scenery")  # none: the default scenery's loading crashes fgfs at times
        os.makedirs(scenery, exist_ok=True)
        command = [FGFS, f"--aircraft={self.aircraft}", f"--fg-scenery={scenery}"] + CHEAPEST + [
            f"--data={d}" for d in self.data_dirs] + [
            f"--generic=socket,in,60,,{INPUT_PORT},udp,hkf", f"--props=socket,bi,60,127.0.0.1,{PROPS_PORT},tcp"]
        if self.max_fps:
            command.append(f"--prop:/sim/frame-rate-throttle-hz={self.max_fps:g}")
        with open(self.fg_log, "w") as f:
            self.fgfs = subprocess.Popen(command, stdout=f, stderr=subprocess.STDOUT, env=env, start_new_session=True)
        return self

    def __exit__(self, *exc):
        self.reading = False
        for sock in (self.props, self.reader):
            if sock is not None:
                sock.close()
        for proc in (self.fgfs, self.xvfb):
            if proc is not None and proc.poll() is None:
                try:
                    os.killpg(proc.pid, signal.SIGTERM) if proc is self.fgfs else proc.terminate()
                    proc.wait(timeout=10)
                except (subprocess.TimeoutExpired, ProcessLookupError):
                    os.killpg(proc.pid, signal.SIGKILL) if proc is self.fgfs else proc.kill()
                    proc.wait(timeout=10)
        return False

    # ---- the property server ----

    def wait_ready(self, limit_s):
        """Until the property server answers and the simulation runs (its flight model initialised, frames
        drawn at a rate): the seconds it took."""
        started = time.time()
        while time.time() - started < limit_s:
            if self.fgfs.poll() is not None:
                raise FlightGearError(f"fgfs exited with status {self.fgfs.returncode} while starting (see {self.fg_log})")
            try:
                if self.props is None:
                    self._connect(limit_s)
                left = max(1.0, limit_s - (time.time() - started))
                if self.get("/sim/signals/fdm-initialized", left) == "true" and \
                        self.get_float("/sim/frame-rate", left) > 0:
                    return time.time() - started
            except (OSError, FlightGearError):  # not listening yet, or closed while it starts: again
                if self.props is not None:
                    self.props.close()
                    self.props = None
            time.sleep(0.5)
        raise FlightGearError(f"FlightGear was not running within {limit_s:.0f} s (its property server answering, "
                              "its flight model initialised)")

    def _connect(self, limit_s):
        self.props = socket.create_connection(("127.0.0.1", PROPS_PORT), timeout=limit_s)
        self.props.sendall(b"data\r\n")
        self.props_file = self.props.makefile("rb")

    def get(self, path, limit_s=60.0, again=5):
        """A property's value as text (answered once a rendered frame). A connection the server reset, closed or
        stopped answering (the c172p does while it settles, more than once at times) is opened again, up to `again`
        times."""
        wait = min(limit_s, 15.0) if again else limit_s  # a connection the server dropped silently: again after 15 s
        try:
            self.props.settimeout(wait)
            self.props.sendall(f"get {path}\r\n".encode())
            answer = self.props_file.readline()  # an empty value is a line of its own: an answer too
        except socket.timeout as e:
            if not again:
                raise FlightGearError(f"FlightGear stopped answering ({path}: no answer in {limit_s:.0f} s)") from e
            answer, error = b"", e
        except OSError as e:
            answer, error = b"", e
        else:
            error = None
        if not answer:
            if again:
                try:
                    self.props.close()
                    self._connect(limit_s)
                except OSError as e:
                    raise FlightGearError(f"FlightGear's property server is gone ({path}: {e})") from e
                return self.get(path, limit_s, again - 1)
            raise FlightGearError(f"FlightGear closed its property server ({path}: {error or 'closed'})")
        return answer.decode().strip()

    def get_float(self, path, limit_s=60.0):
        text = self.get(path, limit_s)
        try:
            return float(text)
        except ValueError as e:
            raise FlightGearError(f"{path} read '{text}', not a number") from e

    def eye_point(self):
        """The aircraft's eye point (m): the view's x/y/z-offset-m before hkf moves it."""
        return [self.get_float(f"/sim/current-view/{axis}-offset-m") for axis in "xyz"]

    # ---- the view read back through the property server, frame by frame ----

    def start_reading(self):
        """A second connection that asks, over and over, for the six view values at once (the property server
        answers the lot in one frame): self.samples gets each set with the time of its last answer. A connection
        the server resets (the c172p does while it settles) is opened again."""
        self.reading = True
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        request = "".join(f"get {VIEW}/{name}\r\n" for name in VIEW_VALUES).encode()
        while self.reading:
            try:
                self.reader = socket.create_connection(("127.0.0.1", PROPS_PORT), timeout=60)
                self.reader.sendall(b"data\r\n")
                answers = self.reader.makefile("rb")
                while self.reading:
                    self.reader.sendall(request)
                    self.samples.append((time.time(), self._answers(answers)))
            except (OSError, ValueError, EOFError) as e:
                if self.reading:
                    self.log(f"the view's read-back connection ended ({e}); again")
                    time.sleep(0.5)

    @staticmethod
    def _answers(answers):
        """The six values answered (blank lines between answers skipped)."""
        values = {}
        for name in VIEW_VALUES:
            line = b""
            while line.strip() == b"":
                line = answers.readline()
                if not line:
                    raise EOFError("closed")
            values[name] = float(line)
        return values

    def heading_answers(self, seconds):
        """(answer s, heading) of gets back to back on the main connection for this long, one at least: one a
        frame."""
        out, end = [], time.time() + seconds
        while not out or time.time() < end:
            value = self.get_float(f"{VIEW}/heading-offset-deg", 30.0)
            out.append((time.time(), value))
        return out

    def screenshot(self, path):
        """The whole screen (the X server's, so a dialog shows too): 0, or the import's status."""
        return subprocess.run(["import", "-window", "root", "-display", f":{self.display}", path],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=30).returncode
