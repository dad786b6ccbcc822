import os, sys, time
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import evaluate, truth_eval
build = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "build"); out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "out", "eval")
os.makedirs(os.path.join(out, "truth", "clips"), exist_ok=True)
sources = [c for c in evaluate.clips() if "shared" in c]
for clip in sources:
    t = time.time()
    truth_eval.make_still_clips(build, out, clip, 2, 4)
    print("done", clip, time.time() - t, flush=True)
for clip in [c for c in sources if os.path.splitext(os.path.basename(c))[0] not in evaluate.TUNING_CLIPS][:2]:
    truth_eval.make_moving_clip(build, out, clip, 4)
    print("moving done", clip, flush=True)
