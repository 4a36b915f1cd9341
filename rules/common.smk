# Names shared by the rules: which notebook draws which paper figure.
from glob import glob

#: notebook stem -> figure stems, in the paper's numbering (figNN_<slug>).
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
}

#: Report section of each notebook.
CATEGORY = {
    "03_constitutive_pictures": "Constitutive pictures (Figs 1-4)",
    "04_forced_vibrations": "Forced vibrations (Figs 5-9)",
    "05_free_vibrations": "Free vibrations (Figs 10-14)",
}

#: Every figure file the pipeline makes.
FIGURE_FILES = [
    f"figures/{stem}.{ext}"
    for stems in NOTEBOOK_FIGURES.values()
    for stem in stems
    for ext in ("pdf", "png")
]

#: Every notebook, executed: build artefacts to read with their outputs.
EXECUTED_NOTEBOOKS = [f"results/notebooks/{name}.ipynb" for name in NOTEBOOK_FIGURES]

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
        caption = f"../report/{stem[:5]}.rst"
        outputs.append(report(png, caption=caption, category=CATEGORY[notebook]))
    return outputs
