"""shadelab.render against the `shadelab` command, pixel for pixel."""

import threading

import numpy as np
import pytest

import shadelab
from conftest import cli_error, run_cli, uv_sphere, write_obj


@pytest.mark.parametrize("model", shadelab.BUILTIN_MODELS)
@pytest.mark.parametrize("shading", shadelab.SHADINGS)
def test_render_equals_the_command_for_every_builtin_model_and_mode(cli, tmp_path, model, shading):
    png = tmp_path / "cli.png"
    run_cli(cli, "render", "--model", model, "--shading", shading, "--size", "120x90",
            "--yaw", "30", "--pitch", "15", "-o", str(png))
    img = shadelab.render(model, shading=shading, size=(120, 90), options={"yaw": 30, "pitch": 15})
    assert img.dtype == np.uint8 and img.shape == (90, 120, 3)
    assert img.flags.c_contiguous
    expected = shadelab.read_png(png)
    assert np.array_equal(img, expected)
    assert (img != 0).any()


def test_camera_lights_material_and_a_scene_file_act_as_in_the_command(cli, tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text('[render]\nwidth = 80\nheight = 60\nbackground = [5, 6, 7]\n[model]\nsource = "torus"\n')
    png = tmp_path / "cli.png"
    run_cli(cli, "render", str(scene), "--shading", "gouraud", "--kd", "20,200,90",
            "--light-pos", "-3,2,4", "--light-intensity", "0.8", "-o", str(png))
    img = shadelab.render(
        scene=scene, shading="gouraud", material={"kd": [20, 200, 90]},
        lights=[{"kind": "point", "position": [-3, 2, 4], "intensity": 0.8}],
    )
    assert np.array_equal(img, shadelab.read_png(png))

    run_cli(cli, "render", "--model", "cube", "--size", "64x64", "-o", str(png))
    framed = shadelab.render("cube", size=(64, 64))
    assert np.array_equal(framed, shadelab.read_png(png))
    moved = shadelab.render("cube", size=(64, 64), camera={"eye": [3, 2, 4], "fov_y": 40})
    assert not np.array_equal(moved, framed)


def test_a_mesh_file_and_the_same_mesh_as_arrays_give_the_same_image(cli, tmp_path):
    vertices, faces = uv_sphere(20)
    path = tmp_path / "ball.obj"
    write_obj(path, vertices, faces)
    for shading in shadelab.SHADINGS:
        from_file = shadelab.render(path, shading=shading, size=(96, 96))
        from_arrays = shadelab.render((vertices, faces), shading=shading, size=(96, 96))
        assert np.array_equal(from_file, from_arrays), shading

        class Duck:  # trimesh's shape: .vertices and .faces
            pass

        duck = Duck()
        duck.vertices, duck.faces = vertices.astype(np.float64), faces.astype(np.int32)
        assert np.array_equal(shadelab.render(duck, shading=shading, size=(96, 96)), from_file)
        png = tmp_path / f"{shading}.png"
        run_cli(cli, "render", "--model", str(path), "--shading", shading, "--size", "96x96", "-o", str(png))
        assert np.array_equal(from_file, shadelab.read_png(png))


def test_alpha_marks_the_pixels_the_model_covers():
    rgba = shadelab.render("sphere", size=(64, 48), alpha=True)
    rgb = shadelab.render("sphere", size=(64, 48))
    assert rgba.shape == (48, 64, 4)
    assert np.array_equal(rgba[..., :3], rgb)
    assert rgba[0, 0, 3] == 0 and rgba[24, 32, 3] == 255
    assert set(np.unique(rgba[..., 3])) == {0, 255}


def test_bad_input_raises_with_the_commands_message(cli, tmp_path):
    missing = tmp_path / "missing.obj"
    with pytest.raises(OSError) as e:
        shadelab.render(missing)
    assert str(e.value) == cli_error(run_cli(cli, "render", "--model", str(missing), "-o", str(tmp_path / "x.png"), check=False))

    broken = tmp_path / "broken.obj"
    broken.write_text("v 0 0 0\nv 1 0 0\nf 1 2 3\n")
    with pytest.raises(ValueError) as e:
        shadelab.render(broken)
    assert str(e.value) == cli_error(run_cli(cli, "render", "--model", str(broken), "-o", str(tmp_path / "x.png"), check=False))

    with pytest.raises(ValueError) as e:
        shadelab.render("teapot", size=(0, 10))
    # `size` is the scene file's render.width/height (the `--size` flag has its
    # own WIDTHxHEIGHT syntax and message), so the same values in a scene file.
    scene = tmp_path / "zero.toml"
    scene.write_text("[render]\nwidth = 0\nheight = 10\n")
    assert str(e.value) == cli_error(run_cli(cli, "render", str(scene), "-o", str(tmp_path / "x.png"), check=False))

    with pytest.raises(ValueError) as e:
        shadelab.render("teapot", material={"shininess": -1})
    # The `--shininess` flag reads its value as the command line does (its
    # message names the flag, then the same words); the scene file's is this one.
    scene = tmp_path / "dull.toml"
    scene.write_text("[material]\nshininess = -1.0\n")
    assert str(e.value) == cli_error(run_cli(cli, "render", str(scene), "-o", str(tmp_path / "x.png"), check=False))
    flag = cli_error(run_cli(cli, "render", "--shininess", "-1", "-o", str(tmp_path / "x.png"), check=False))
    assert flag.endswith(str(e.value)), flag

    with pytest.raises(ValueError, match="model.source"):
        shadelab.render("no-such-model")
    with pytest.raises(ValueError, match="shading"):
        shadelab.render("cube", shading="smooth")
    vertices, faces = uv_sphere(8)
    with pytest.raises(ValueError, match="refers to vertex"):
        shadelab.render((vertices, faces + 1000))
    with pytest.raises(ValueError, match="not a vertex index"):
        shadelab.render((vertices, faces - 1))
    with pytest.raises(ValueError, match=r"shape \(N, 3\)"):
        shadelab.render((vertices[:, :2], faces))
    with pytest.raises(ValueError, match="integer"):
        shadelab.render((vertices, faces.astype(np.float32)))
    with pytest.raises(ValueError, match="not a finite number"):
        bad = vertices.copy()
        bad[0, 0] = np.nan
        shadelab.render((bad, faces))
    with pytest.raises(ValueError):
        shadelab.render(42)


def test_four_threads_rendering_at_once_get_the_right_images():
    jobs = [(m, s) for m in ("teapot", "torus", "sphere", "cone") for s in shadelab.SHADINGS]
    expected = {job: shadelab.render(job[0], shading=job[1], size=(160, 120)) for job in jobs}
    got = {}
    errors = []
    barrier = threading.Barrier(4)

    def work(k):
        try:
            barrier.wait()
            for _ in range(3):
                for job in jobs[k::4]:
                    img = shadelab.render(job[0], shading=job[1], size=(160, 120))
                    assert job not in got or np.array_equal(got[job], img)
                    got[job] = img
        except Exception as e:  # reported below, not lost in the thread
            errors.append(e)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    assert got.keys() == expected.keys()
    for job, img in expected.items():
        assert np.array_equal(got[job], img), job
