# Names shared by the rules: the checked configuration, and which notebook draws
# which paper figure.
import sys
from glob import glob

import yaml

import lumped.studies.config


def checked_config(raw):
    """The configuration with values coerced, or exit 2 with one line per problem.

    The check is lumped.studies.config's, the same the notebooks run when they read the
    configuration. Exiting from the Snakefile prints only our lines; a
    WorkflowError would add the file, line and a traceback frame.
    """
    # The --config texts too: Snakemake reads gamma=1e400 as inf, which the values cannot tell from gamma=inf.
    problems = lumped.studies.config.problems(raw, list(workflow.config_settings.config_args or []))
    if problems:
        print("\n".join(problems), file=sys.stderr)
        sys.exit(2)
    return lumped.studies.config.check(raw)


config.update(checked_config(config))
#: The configuration as canonical text (keys sorted, floats by repr): the
#: effective_config rule's parameter, so that an override equal to the default
#: (dt=1e-4 against 1.0e-4, or keys in another order) changes nothing.
CONFIG_TEXT = yaml.safe_dump(dict(config), sort_keys=True)

#: notebook stem -> figure stems: the paper's in its numbering (figNN_<slug>),
#: then the tutorial's extensions (extNN_<slug>, notebooks 06 to 08) and the
#: accuracy study (accNN_<slug>, notebook 09) and the studies (stNN_<slug>, notebook 10;
#: spNN_<slug>, notebook 12; rcNN_<slug>, notebook 13; fitNN_<slug>, notebook 14;
#: frNN_<slug>, notebook 15; cyNN_<slug>, notebook 16; bkNN_<slug>, notebook 17).
NOTEBOOK_FIGURES = {
    "01_governing_equations": [],
    "02_sgn_zero_failure": [],
    "03_constitutive_pictures": [
        "fig01_bingham_relations",
        "fig02_spring_with_string",
        "fig03_mass_spring_dashpot",
        "fig04_bingham_pictorial",
    ],
    "04_forced_vibrations": [
        "fig05_forced_small",
        "fig06_forced_large_x",
        "fig07_forced_large_v",
        "fig08_forced_large_Fs",
        "fig09_forced_large_Fd",
    ],
    "05_free_vibrations": [
        "fig10_free_small",
        "fig11_free_large_x",
        "fig12_free_large_v",
        "fig13_free_large_Fs",
        "fig14_free_large_Fd",
    ],
    "06_implicit_spring": ["ext01_spring_string_impact"],
    "07_maxwell_and_locking": [
        "ext02_maxwell_relaxation",
        "ext03_locking_graph",
        "ext04_locking_run",
    ],
    "08_chain_stick_slip": [
        "ext05_chain_stick_map",
        "ext06_chain_positions",
    ],
    "09_which_method": ["acc01_convergence", "acc02_work_precision"],
    "10_where_it_rests": ["st01_rest_position", "st02_wrong_side"],
    "11_den_hartog": ["dh01_amplitude", "dh02_steady_state"],
    "12_stops_per_cycle": ["sp01_stops_map", "sp02_stop_histories"],
    "13_response_curves": ["rc01_response_curves", "rc02_two_mass_response"],
    "14_sensitivities_and_fit": ["fit01_rest_kinks", "fit02_free_decay_fit"],
    "15_friction_on_a_belt": ["fr01_belt_phase_portrait", "fr02_smoothing_creep", "fr03_stribeck_stability"],
    "16_self_excited_cycles": ["cy01_bifurcation_leine", "cy02_bifurcation_stribeck"],
    "17_burridge_knopoff": ["bk01_slip_event", "bk02_event_sizes"],
}

#: notebook stem -> the data files it reads (rules/studies.smk, rules/accuracy.smk).
NOTEBOOK_DATA = {
    "09_which_method": ["results/accuracy/study.json"],
    "10_where_it_rests": ["results/studies/rest.csv"],
    "11_den_hartog": ["results/studies/den_hartog.csv"],
    "12_stops_per_cycle": ["results/studies/stops.csv", "results/studies/stops_low.csv"],
    "13_response_curves": ["results/studies/den_hartog.csv", "examples/two_mass_response.toml"],
    "17_burridge_knopoff": ["results/studies/burridge_knopoff.csv", "results/studies/burridge_knopoff.json"],
}

#: The report's category of each notebook's figures.  No colon in a name: Snakemake writes
#: ``.. _<category>: javascript:...`` for each, and docutils reads a colon as the end of the
#: target's name (tests/test_report.py).
CATEGORY = {
    "03_constitutive_pictures": "Constitutive pictures (Figs 1-4)",
    "04_forced_vibrations": "Forced vibrations (Figs 5-9)",
    "05_free_vibrations": "Free vibrations (Figs 10-14)",
    "06_implicit_spring": "Tutorial - the implicit spring (ext01)",
    "07_maxwell_and_locking": "Tutorial - Maxwell and locking elements (ext02-ext04)",
    "08_chain_stick_slip": "Tutorial - stick-slip along a chain (ext05-ext06)",
    "09_which_method": "Tutorial - which method, when (acc01-acc02)",
    "10_where_it_rests": "Study - where the mass comes to rest (st01-st02)",
    "11_den_hartog": "Study - Den Hartog's forced oscillator with friction (dh01-dh02)",
    "12_stops_per_cycle": "Study - stops per cycle of the forced Coulomb oscillator (sp01-sp02)",
    "13_response_curves": "Tutorial - response curves by shooting and continuation (rc01-rc02)",
    "14_sensitivities_and_fit": "Tutorial - sensitivities through stick and slip, and a fit (fit01-fit02)",
    "15_friction_on_a_belt": "Tutorial - friction on a belt, static above kinetic and Stribeck (fr01-fr03)",
    "16_self_excited_cycles": "Tutorial - self-excited cycles, from steady sliding to stick-slip (cy01-cy02)",
    "17_burridge_knopoff": "Study - the Burridge-Knopoff chain, Carlson and Langer's earthquake model (bk01-bk02)",
}

#: Every figure file the pipeline makes.
FIGURE_FILES = [
    f"figures/{stem}.{ext}"
    for stems in NOTEBOOK_FIGURES.values()
    for stem in stems
    for ext in ("pdf", "png")
]

#: The paper's figures (figNN_*.pdf), the ones the article embeds; the tutorial's
#: extNN figures are not part of the replication.
PAPER_FIGURE_PDFS = [f for f in FIGURE_FILES if f.startswith("figures/fig") and f.endswith(".pdf")]

#: Every notebook, executed: build artefacts to read with their outputs.
EXECUTED_NOTEBOOKS = [f"results/notebooks/{name}.ipynb" for name in NOTEBOOK_FIGURES]

#: The caption of each figure (stem -> file), reStructuredText: the report's and the website's.
CAPTIONS = {stem: f"report/{stem.split('_')[0]}.rst" for stems in NOTEBOOK_FIGURES.values() for stem in stems}

#: The package sources: editing any of them reruns every notebook.
PACKAGE_SOURCES = sorted(
    glob("src/lumped/**/*.py", recursive=True) + glob("src/lumped/**/*.mplstyle", recursive=True)
)


def notebook_outputs(notebook):
    """The figures of one notebook, PNGs listed in the report with their captions."""
    outputs = []
    for stem in NOTEBOOK_FIGURES[notebook]:
        outputs.append(f"figures/{stem}.pdf")
        png = f"figures/{stem}.png"
        outputs.append(report(png, caption=f"../{CAPTIONS[stem]}", category=CATEGORY[notebook]))
    return outputs
