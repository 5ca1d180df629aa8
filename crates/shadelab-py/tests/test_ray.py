"""examples/ray_batch.py on a local Ray: the images equal the command's."""

import importlib.util
import sys

import ray

from conftest import REPO, run_cli
from test_batch import files, make_set


def load_example():
    spec = importlib.util.spec_from_file_location("ray_batch", REPO / "examples" / "ray_batch.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["ray_batch"] = module
    spec.loader.exec_module(module)
    return module


def test_ray_tasks_render_the_manifest_as_the_command_does(cli, tmp_path):
    manifest = make_set(tmp_path, count=8)
    example = load_example()
    # Workers import the example's module by name, as they would on a cluster.
    examples = str(REPO / "examples")
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False,
             runtime_env={"env_vars": {"PYTHONPATH": examples}})
    try:
        args = ["--views", "2", "--shading", "all", "--size", "48x40", "--chunk", "3"]
        total = example.main([str(manifest), "-o", str(tmp_path / "ray"), *args])
        assert (total["meshes"], total["written"], total["failed"], total["tasks"]) == (9, 48, 6, 3)
        again = example.main([str(manifest), "-o", str(tmp_path / "ray"), *args])
        assert (again["written"], again["skipped"]) == (0, 48)
    finally:
        ray.shutdown()
    run_cli(cli, "batch", str(manifest), "-o", str(tmp_path / "cli"), "--views", "2",
            "--shading", "all", "--size", "48x40", "--progress", "none")
    ray_files = files(tmp_path / "ray")
    assert len(ray_files) == 48
    assert ray_files == files(tmp_path / "cli")
