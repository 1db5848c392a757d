"""Bazel rules for texproc: one cached action per texture.

    load("@texproc_rules//:texproc.bzl", "texproc_texture", "texproc_textures")

texproc_tool_repository(name, texproc)   the texproc binary and its runtime modules
texproc_texture(name, src, out, command, args)   one texture
texproc_textures(name, srcs, command, out_dir, extension, args)   one action per source
texproc_recipe(name, recipe, texproc)    a recipe's actions (texproc build --emit-actions): @NAME//:NAME

Every action runs `texproc COMMAND SRC -o OUT ARGS... -q` with the binary and
its modules as declared inputs, so it runs the same in the local sandbox, from
a remote cache, and on a remote executor. See docs/scale-out.md.
"""

TexprocToolInfo = provider(
    doc = "The texproc executable and the files it runs with.",
    fields = {
        "executable": "File: the texproc binary",
        "runtime": "depset of Files: the binary and its runtime modules",
    },
)

def _texproc_tool_impl(ctx):
    runtime = depset([ctx.file.binary] + ctx.files.modules)
    return [
        TexprocToolInfo(executable = ctx.file.binary, runtime = runtime),
        DefaultInfo(files = runtime),
    ]

texproc_tool = rule(
    implementation = _texproc_tool_impl,
    doc = "texproc as a tool target: the binary with its runtime modules beside it.",
    attrs = {
        "binary": attr.label(allow_single_file = True, mandatory = True),
        "modules": attr.label_list(allow_files = [".so"]),
    },
)

def _find_texproc(rctx, rule):
    # The texproc binary: the rule's `texproc`, else $TEXPROC, else PATH.
    texproc = rctx.attr.texproc or rctx.os.environ.get("TEXPROC", "")
    if texproc:
        return texproc
    found = rctx.which("texproc")
    if not found:
        fail("%s: name the texproc binary (texproc = ..., or $TEXPROC), or put it on PATH" % rule)
    return str(found)

def _tool_repository_impl(rctx):
    texproc = _find_texproc(rctx, "texproc_tool_repository")
    listed = rctx.execute([texproc, "--runtime-files"])
    if listed.return_code != 0:
        fail("%s --runtime-files failed: %s" % (texproc, listed.stderr))
    files = [f for f in listed.stdout.splitlines() if f]

    # Copies, not links: the binary finds its modules beside itself, in the
    # sandbox and on a remote executor alike.
    names = []
    for f in files:
        name = "bin/" + f.rsplit("/", 1)[-1]
        result = rctx.execute(["mkdir", "-p", "bin"])
        result = rctx.execute(["cp", "-p", f, name])
        if result.return_code != 0:
            fail("cannot copy %s: %s" % (f, result.stderr))
        names.append(name)
    binary = names[0]
    modules = names[1:]
    rctx.file("BUILD.bazel", """load("@{rules}//:texproc.bzl", "texproc_tool")

texproc_tool(
    name = "texproc",
    binary = "{binary}",
    modules = {modules},
    visibility = ["//visibility:public"],
)
""".format(rules = rctx.attr.rules_repository, binary = binary, modules = repr(modules)))

texproc_tool_repository = repository_rule(
    implementation = _tool_repository_impl,
    doc = "Copies a texproc binary and its runtime modules (texproc --runtime-files) into a repository " +
          "with the target :texproc. Fetched again when `texproc` or $TEXPROC changes, or by " +
          "`bazel sync --only=NAME` after texproc was rebuilt in place.",
    attrs = {
        "texproc": attr.string(doc = "Path of the texproc binary (default: $TEXPROC, then PATH)"),
        "rules_repository": attr.string(default = "texproc_rules", doc = "The name this file's repository has"),
    },
    environ = ["TEXPROC"],
    local = True,
)

def _run_texproc(ctx, command, inputs, outputs, arguments):
    tool = ctx.attr.tool[TexprocToolInfo]
    ctx.actions.run(
        executable = tool.executable,
        arguments = arguments,
        inputs = depset(inputs, transitive = [tool.runtime]),
        outputs = outputs,
        mnemonic = "Texproc",
        progress_message = "texproc %s %s" % (command, outputs[0].short_path),
    )

def _texproc_texture_impl(ctx):
    out = ctx.actions.declare_file(ctx.attr.out)
    arguments = ctx.attr.command.split(" ") + [ctx.file.src.path, "-o", out.path]
    arguments += [ctx.expand_location(a, ctx.attr.data) for a in ctx.attr.args] + ["-q"]
    _run_texproc(ctx, ctx.attr.command, [ctx.file.src] + ctx.files.data, [out], arguments)
    return [DefaultInfo(files = depset([out]))]

_TOOL = attr.label(default = "@texproc//:texproc", providers = [TexprocToolInfo], cfg = "exec")

texproc_texture = rule(
    implementation = _texproc_texture_impl,
    doc = "One texture: texproc COMMAND SRC -o OUT ARGS... (one output file: a container such as .dds or .ktx2).",
    attrs = {
        "src": attr.label(allow_single_file = True, mandatory = True),
        "out": attr.string(mandatory = True, doc = "Output file, relative to the package"),
        "command": attr.string(default = "compress", doc = "mip, compress, normalmap, conemap, sat, decompress..."),
        "args": attr.string_list(doc = "Options, as on the command line ($(location) for files in data)"),
        "data": attr.label_list(allow_files = True, doc = "Files the options name (a radius map, an OCIO config)"),
        "tool": _TOOL,
    },
)

def texproc_textures(name, srcs, out_dir, extension, command = "compress", args = [], data = [], strip_prefix = "", **kwargs):
    """One texproc_texture per source, OUT_DIR/STEM.EXTENSION (sub-folders after strip_prefix kept).

    `name` is a filegroup of every output."""
    outs = []
    for src in srcs:
        path = src.split(":")[-1]
        if strip_prefix and path.startswith(strip_prefix):
            path = path[len(strip_prefix):].lstrip("/")
        stem = path.rsplit(".", 1)[0]
        target = "%s__%s" % (name, stem.replace("/", "_"))
        texproc_texture(
            name = target,
            src = src,
            out = "%s/%s%s" % (out_dir, stem, extension),
            command = command,
            args = args,
            data = data,
            **kwargs
        )
        outs.append(":" + target)
    native.filegroup(name = name, srcs = outs, **kwargs)

def _texproc_action_impl(ctx):
    outs = ctx.outputs.outs

    # The recipe names outputs relative to its folder; here they live under
    # this package's output root.
    root = outs[0].path[:-len(ctx.attr.out_names[0])]
    arguments = []
    for a in ctx.attr.argv[1:]:
        if a.startswith("$(location"):
            arguments.append(ctx.expand_location(a, ctx.attr.srcs))
        elif a.startswith("@OUT@"):
            arguments.append(root + a[len("@OUT@"):])
        else:
            arguments.append(a)
    _run_texproc(ctx, ctx.attr.argv[1], ctx.files.srcs, outs, arguments + ["-q"])
    return [DefaultInfo(files = depset(outs))]

texproc_action = rule(
    implementation = _texproc_action_impl,
    doc = "One action of a recipe, as texproc build --emit-actions gives it (made by texproc_recipe).",
    attrs = {
        "argv": attr.string_list(mandatory = True),
        "srcs": attr.label_list(allow_files = True),
        "outs": attr.output_list(mandatory = True),
        "out_names": attr.string_list(mandatory = True, doc = "outs as paths relative to the package"),
        "tool": _TOOL,
    },
)

def _label_of(recipe, path):
    # A path relative to the recipe's folder as a label of the recipe's repository.
    parts = recipe.package.split("/") if recipe.package else []
    for p in path.split("/"):
        if p == "..":
            if not parts:
                fail("%s: %s lies outside the recipe's repository" % (recipe, path))
            parts.pop()
        elif p and p != ".":
            parts.append(p)
    depth = len(recipe.package.split("/")) if recipe.package else 0
    if parts[:depth] != (recipe.package.split("/") if recipe.package else []):
        fail("%s: %s lies outside the recipe's package; keep a recipe's sources under its folder" % (recipe, path))
    return "@%s//%s:%s" % (recipe.workspace_name, recipe.package, "/".join(parts[depth:]))

# Options whose value is an output file (besides -o).
_OUTPUT_OPTIONS = ["-o", "--preview"]

def _recipe_impl(rctx):
    texproc = _find_texproc(rctx, "texproc_recipe")
    recipe = rctx.path(rctx.attr.recipe)
    result = rctx.execute([texproc, "build", str(recipe), "--emit-actions"])
    if result.return_code != 0:
        fail("texproc build --emit-actions failed:\n" + result.stderr)
    actions = json.decode(result.stdout)["actions"]
    made = {}
    for a in actions:
        for o in a["outputs"]:
            made[o] = True
    lines = ['load("@%s//:texproc.bzl", "texproc_action")' % rctx.attr.rules_repository, ""]
    all_outs = []
    for i, a in enumerate(actions):
        if not a["outputs_known"]:
            fail("%s: the outputs of `%s` depend on its input; give the job a container output (.dds, .ktx2) or --levels" %
                 (rctx.attr.recipe, " ".join(a["argv"])))
        srcs = []
        argv = []
        output_next = False
        for arg in a["argv"]:
            if output_next:
                argv.append("@OUT@" + arg)
                output_next = False
                continue
            output_next = arg in _OUTPUT_OPTIONS
            if arg in a["inputs"]:
                label = (":" + arg) if arg in made else _label_of(rctx.attr.recipe, arg)
                srcs.append(label)
                argv.append("$(location %s)" % label)
            else:
                argv.append(arg)
        for f in a["inputs"]:
            label = (":" + f) if f in made else _label_of(rctx.attr.recipe, f)
            if label not in srcs:
                srcs.append(label)
        lines.append("texproc_action(name = %s, argv = %s, srcs = %s, outs = %s, out_names = %s, tool = %s)" % (
            repr("action_%d" % i), repr(argv), repr(srcs), repr(a["outputs"]), repr(a["outputs"]), repr(rctx.attr.tool)))
        all_outs += [":" + o for o in a["outputs"]]
    lines.append("")
    lines.append("filegroup(name = %s, srcs = %s, visibility = [\"//visibility:public\"])" % (repr(rctx.name), repr(all_outs)))
    rctx.file("BUILD.bazel", "\n".join(lines) + "\n")

texproc_recipe = repository_rule(
    implementation = _recipe_impl,
    doc = "A recipe's actions as targets: one texproc_action per file (texproc build --emit-actions), and " +
          "@NAME//:NAME, every output. " +
          "Fetched again when the recipe changes; `bazel sync --only=NAME` after files were added.",
    attrs = {
        "recipe": attr.label(mandatory = True, allow_single_file = True),
        "texproc": attr.string(doc = "Path of the texproc binary (default: $TEXPROC, then PATH)"),
        "tool": attr.string(default = "@texproc//:texproc", doc = "The texproc_tool target the actions run"),
        "rules_repository": attr.string(default = "texproc_rules", doc = "The name this file's repository has"),
    },
    environ = ["TEXPROC"],
    local = True,
)
