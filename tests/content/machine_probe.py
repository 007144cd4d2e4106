"""What a student reads and what the grader expects, as plain JSON: the probe of test_same_numbers_everywhere.

``python tests/content/machine_probe.py '[stereo variants]' '[task variants]'`` prints it; the test runs it under
another machine's arithmetic and compares it with :func:`collect` in its own process.
"""

from __future__ import annotations

import json
import sys

import numpy as np


def plain(x):
    """``x`` (frames, series, arrays, numbers) as JSON values; numbers as floats."""
    if hasattr(x, "to_dict"):
        return plain(x.to_dict())
    if isinstance(x, dict):
        return {str(k): plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple, np.ndarray)):
        return [plain(v) for v in x]
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, float, np.integer, np.floating)):
        return float(x)
    return str(x)


def collect(stereo_variants, task_variants) -> dict:
    """``{"stereo": {variant: the pair's readings}, "answers": {"task-… vNN": the task's answers}}``: chapter 07's
    stereo labs (and the guide's example pair) as the student reads them, and every task's reference answers."""
    from aerophoto import tasks
    from aerophoto.labs.ch07 import example_lab, stereo_lab
    from aerophoto.variants import variant_for_index

    labs = {"example": example_lab()} | {str(i): stereo_lab(variant_for_index(int(i))) for i in stereo_variants}
    stereo = {k: {"objects": plain(lab.objects_table().round(3)), "control": plain(lab.control),
                  "principal": plain(lab.principal)} for k, lab in labs.items()}
    answers = {}
    for i in task_variants:
        v = variant_for_index(int(i))
        for task in tasks.all_tasks():
            answers[f"{task.id} v{int(i):02d}"] = plain(task.answers(v))
    # through JSON, as the subprocess's side comes
    return json.loads(json.dumps({"stereo": stereo, "answers": answers}))


if __name__ == "__main__":
    print(json.dumps(collect(json.loads(sys.argv[1]), json.loads(sys.argv[2]))))
