"""Every class of bad input the API shares with the `hcm` command is refused with the
command's own message (its standard error after `error: `)."""

import pytest

import hcm

BALL = "scenarios/bouncing_ball.toml"
PM2 = "examples/blobs/bouncing_ball.pm2.toml"


def write(folder, name, text):
    path = folder / name
    path.write_text(text)
    return path


# (class, the CLI's arguments, the same input through Python); `{tmp}` files are made
# by `files` below.
CASES = [
    ("unknown law", ["force", "--law", "hurtz", "--depth", "1e-5"], lambda t: hcm.Law("hurtz")),
    (
        "missing law parameter",
        ["force", "--law", "hertz", "--set", "stiffness=1e9", "--depth", "1e-5"],
        lambda t: hcm.Law("hertz", stiffness=1e9),
    ),
    (
        "unknown law parameter",
        ["force", "--law", "hertz", "--set", "stiffness=1e9", "--set", "exponent=1.5", "--set", "damping=3", "--depth", "1e-5"],
        lambda t: hcm.Law("hertz", stiffness=1e9, exponent=1.5, damping=3),
    ),
    (
        "law parameter out of its domain",
        ["force", "--law", "hertz", "--set", "stiffness=-1e9", "--set", "exponent=1.5", "--depth", "1e-5"],
        lambda t: hcm.Law("hertz", stiffness=-1e9, exponent=1.5),
    ),
    (
        "scenario file missing",
        ["simulate", "--scenario", "{tmp}/absent.toml", "--out", "{tmp}/out.csv"],
        lambda t: hcm.Scenario.load(t / "absent.toml"),
    ),
    (
        "scenario not TOML",
        ["simulate", "--scenario", "{tmp}/broken.toml", "--out", "{tmp}/out.csv"],
        lambda t: hcm.Scenario.load(t / "broken.toml"),
    ),
    (
        "override of an absent key",
        ["simulate", "--scenario", BALL, "--set", "body.rock.velocity=[0,0,-1]", "--out", "{tmp}/out.csv"],
        lambda t: hcm.Scenario.load(BALL, set=["body.rock.velocity=[0,0,-1]"]),
    ),
    (
        "override not key=value",
        ["simulate", "--scenario", BALL, "--set", "contact.0.law", "--out", "{tmp}/out.csv"],
        lambda t: hcm.Scenario.load(BALL).with_set(["contact.0.law"]),
    ),
    (
        "scenario with a law's wrong parameter",
        ["simulate", "--scenario", BALL, "--set", "contact.0.law=\"hertz\"", "--out", "{tmp}/out.csv"],
        lambda t: hcm.simulate(hcm.Scenario.load(BALL, set=['contact.0.law="hertz"'])),
    ),
    (
        "physics file missing",
        ["simulate", "--scenario", BALL, "--physics", "{tmp}/absent_pm2.toml", "--out", "{tmp}/out.csv"],
        lambda t: hcm.Scenario.load(BALL).with_physics(t / "absent_pm2.toml"),
    ),
    (
        "physics file for other bodies",
        ["simulate", "--scenario", BALL, "--physics", "{tmp}/other_pm2.toml", "--out", "{tmp}/out.csv"],
        lambda t: hcm.Scenario.load(BALL).with_physics(t / "other_pm2.toml"),
    ),
    (
        "data file with a bad number",
        ["indicators", "--scenario", BALL, "--data", "{tmp}/bad.csv"],
        lambda t: hcm.Dataset.read_csv(t / "bad.csv"),
    ),
    (
        "data file without its columns",
        ["indicators", "--scenario", BALL, "--data", "{tmp}/headless.csv"],
        lambda t: hcm.Dataset.read_csv(t / "headless.csv"),
    ),
    (
        "too few runs for S1 and S2",
        ["generate", "--scenario", BALL, "--runs", "1", "--out", "{tmp}/pm1.csv"],
        lambda t: hcm.generate(hcm.Scenario.load(BALL), runs=1),
    ),
    (
        "a fit without its law",
        ["identify", "--scenario", BALL, "--data", "{tmp}/s1.csv", "--out", "{tmp}/pm2.toml"],
        lambda t: hcm.identify(hcm.Scenario.load(BALL), hcm.Dataset.read_csv(t / "s1.csv")),
    ),
    (
        "a contact the scenario lacks",
        ["identify", "--scenario", BALL, "--data", "{tmp}/s1.csv", "--law", "hertz", "--contact", "3", "--out", "{tmp}/pm2.toml"],
        lambda t: hcm.identify(hcm.Scenario.load(BALL), hcm.Dataset.read_csv(t / "s1.csv"), law="hertz", contact=3),
    ),
    (
        "a negative run count",
        ["generate", "--scenario", BALL, "--runs", "-3", "--out", "{tmp}/pm1.csv"],
        lambda t: hcm.generate(hcm.Scenario.load(BALL), runs=-3),
    ),
    (
        "a population of one",
        ["identify", "--scenario", BALL, "--data", "{tmp}/s1.csv", "--law", "hertz", "--method", "ga", "--population", "1", "--out", "{tmp}/pm2.toml"],
        lambda t: hcm.identify(hcm.Scenario.load(BALL), hcm.Dataset.read_csv(t / "s1.csv"), law="hertz", method="ga", population=1),
    ),
    (
        "no training epochs",
        ["train", "--scenario", BALL, "--physics", PM2, "--data", "{tmp}/s1.csv", "--epochs", "0", "--out", "{tmp}/r.json"],
        lambda t: hcm.train(hcm.Scenario.load(BALL), hcm.Physics.read(PM2), hcm.Dataset.read_csv(t / "s1.csv"), epochs=0),
    ),
    (
        "a negative seed",
        ["generate", "--scenario", BALL, "--runs", "12", "--seed", "-1", "--out", "{tmp}/pm1.csv"],
        lambda t: hcm.generate(hcm.Scenario.load(BALL), runs=12, seed=-1),
    ),
    (
        "no worker thread",
        ["--threads", "0", "laws"],
        lambda t: hcm.set_threads(0),
    ),
    (
        "data file missing",
        ["indicators", "--scenario", BALL, "--data", "{tmp}/absent.csv"],
        lambda t: hcm.Dataset.read_csv(t / "absent.csv"),
    ),
    (
        "data of another scene's bodies",
        ["identify", "--scenario", BALL, "--data", "{tmp}/cube.csv", "--law", "hertz", "--out", "{tmp}/pm2.toml"],
        lambda t: hcm.identify(hcm.Scenario.load(BALL), hcm.Dataset.read_csv(t / "cube.csv"), law="hertz"),
    ),
    (
        "an output folder that is a file",
        ["diagnose", "--scenario", BALL, "--physics", PM2, "--data", "{tmp}/s1.csv", "--out", "{tmp}/broken.toml"],
        lambda t: hcm.diagnose(hcm.Scenario.load(BALL), hcm.Physics.read(PM2), hcm.Dataset.read_csv(t / "s1.csv"), out=t / "broken.toml"),
    ),
    (
        "a hold-out share outside (0, 1)",
        ["diagnose", "--scenario", BALL, "--physics", PM2, "--data", "{tmp}/s1.csv", "--holdout", "1.5", "--out", "{tmp}/d"],
        lambda t: hcm.diagnose(hcm.Scenario.load(BALL), hcm.Physics.read(PM2), hcm.Dataset.read_csv(t / "s1.csv"), holdout=1.5),
    ),
]


@pytest.fixture
def files(tmp_path, cli):
    write(tmp_path, "broken.toml", "name = \"x\"\n[body.ball\nmass = 1\n")
    write(
        tmp_path,
        "other_pm2.toml",
        '[[contact]]\nbodies = ["peg", "hole"]\nlaw = "hertz"\n\n[contact.parameters]\nstiffness = 1e9\nexponent = 1.5\n',
    )
    header = "run,body,time,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,fx,fy,fz,tx,ty,tz\n"
    write(tmp_path, "bad.csv", header + "0,ball,0.0" + ",0" * 15 + ",1.5e,0,0,0\n")
    write(tmp_path, "headless.csv", "0,ball,0.0\n")
    cli.ok("generate", "--scenario", BALL.replace("bouncing_ball", "cube_drop"), "--runs", "2",
           "--out", tmp_path / "cube.csv")
    cli.ok("generate", "--scenario", BALL, "--runs", "12", "--out", tmp_path / "pm1.csv")
    (tmp_path / "pm1.s1.csv").rename(tmp_path / "s1.csv")
    (tmp_path / "pm1.csv").unlink()
    return tmp_path


@pytest.mark.parametrize("name, arguments, call", CASES, ids=[c[0] for c in CASES])
def test_python_raises_the_cli_s_message(cli, root, files, monkeypatch, name, arguments, call):
    arguments = [a.replace("{tmp}", str(files)) for a in arguments]
    expected = cli.refusal(*arguments)
    # An option's value refused by its parser: clap adds where to read more.
    expected = expected.removesuffix("\n\nFor more information, try '--help'.")
    monkeypatch.chdir(root)
    with pytest.raises(hcm.HcmError) as raised:
        call(files)
    assert str(raised.value) == expected
