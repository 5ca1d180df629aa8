"""What the timing scripts of bench/ (ab.py, threads.py, ab_placed.py) share:
where the models are, and one call of `shadelab bench --json`.

The models are read from ../shared/models beside the repository, or from
$SHADELAB_MODELS.
"""
import json, os, subprocess

MODELS = os.environ.get('SHADELAB_MODELS') or os.path.join(
    os.path.dirname(os.path.abspath(__file__)), '..', '..', 'shared', 'models')


def bench_json(binary, args):
    """`BINARY bench --json --models-dir MODELS ARGS...`, its JSON parsed."""
    out = subprocess.run([binary, 'bench', '--json', '--models-dir', MODELS] + list(args),
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out)
