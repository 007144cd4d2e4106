"""What a student reads and what the grader expects, as plain JSON: the probe of test_same_numbers_everywhere.

``python tests/content/machine_probe.py '[stereo variants]' '[task variants]'`` prints it; the test runs it under
another machine's arithmetic and compares it with :func:`collect` in its own process.
"""

from __future__ import annotations

import json
import sys

from aerophoto.report.facts import plain  # numpy and pandas values as plain JSON data


def collect(stereo_variants, task_variants) -> dict:
    """``{"stereo": {variant: the pair's readings}, "answers": {"task-… vNN": the task's answers}}``: chapter 07's
    stereo labs (and the guide's example pair) as the student reads them, and every task's reference answers."""
    from aerophoto import tasks
    from aerophoto.labs.ch07 import example_lab, stereo_lab
    from aerophoto.variants import variant_for_index

    labs = {"example": example_lab()} | {str(i): stereo_lab(variant_for_index(int(i))) for i in stereo_variants}
    stereo = {k: {"objects": plain(lab.objects_table().round(3).to_dict()), "control": plain(lab.control.to_dict()),
                  "principal": plain(lab.principal.to_dict())} for k, lab in labs.items()}
    answers = {}
    for i in task_variants:
        v = variant_for_index(int(i))
        for task in tasks.all_tasks():
            answers[f"{task.id} v{int(i):02d}"] = plain(task.answers(v))
    return {"stereo": stereo, "answers": answers}


if __name__ == "__main__":
    print(json.dumps(collect(json.loads(sys.argv[1]), json.loads(sys.argv[2]))))
