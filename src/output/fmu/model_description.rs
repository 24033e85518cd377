//! `modelDescription.xml` of a ROM's FMU (FMI 2.0 §2.2): the variables in value-reference
//! order (inputs, outputs, states, then for a continuous ROM the states' derivatives), the
//! inputs' and outputs' units (a state's description says what it measures), and the model structure (every output and derivative depends on the states and
//! inputs).

use super::super::rom_export::RomExport;

/// `text` with XML's special characters escaped, for an attribute value.
fn escaped(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if (c as u32) < 0x20 => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// The unit attribute of a unit name (none for a dimensionless or unknown unit).
fn unit_attribute(unit: Option<&String>) -> String {
    match unit.map(|u| u.trim()).filter(|u| !u.is_empty() && *u != "-" && *u != "1") {
        Some(u) => format!(" unit=\"{}\"", escaped(u)),
        None => String::new(),
    }
}

/// The document for `export`, model identifier `id`, GUID `guid`.
pub fn xml(export: &RomExport, id: &str, guid: &str) -> String {
    let (n, m, p) = (export.a.nrows(), export.b.ncols(), export.c.nrows());
    let discrete = export.sample_time.is_some();
    // Inputs and outputs are continuous (a discrete ROM samples its inputs; its outputs
    // follow them through D); a discrete ROM's states change at its samples only.
    let variability = "continuous";
    let state_variability = if discrete { "discrete" } else { "continuous" };
    let mut units: Vec<&str> = export.input_units.iter().chain(&export.output_units).map(|u| u.trim()).filter(|u| !u.is_empty() && *u != "-" && *u != "1").collect();
    units.sort_unstable();
    units.dedup();

    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let description = format!("{} ROM written by romdyn {} ({}); SI units", export.kind, env!("CARGO_PKG_VERSION"), export.time_domain());
    s += &format!(
        "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{}\" guid=\"{guid}\" description=\"{}\" generationTool=\"romdyn {}\" variableNamingConvention=\"flat\" numberOfEventIndicators=\"0\">\n",
        escaped(id),
        escaped(&description),
        env!("CARGO_PKG_VERSION")
    );
    let sources = format!("    <SourceFiles>\n      <File name=\"{id}.c\"/>\n    </SourceFiles>\n");
    s += &format!("  <ModelExchange modelIdentifier=\"{id}\" canNotUseMemoryManagementFunctions=\"true\">\n{sources}  </ModelExchange>\n");
    s += &format!("  <CoSimulation modelIdentifier=\"{id}\" canHandleVariableCommunicationStepSize=\"true\" canNotUseMemoryManagementFunctions=\"true\">\n{sources}  </CoSimulation>\n");
    if !units.is_empty() {
        s += "  <UnitDefinitions>\n";
        for u in &units {
            s += &format!("    <Unit name=\"{}\"/>\n", escaped(u));
        }
        s += "  </UnitDefinitions>\n";
    }
    if let Some(t) = export.sample_time {
        s += &format!("  <DefaultExperiment stepSize=\"{t:e}\"/>\n");
    }
    s += "  <ModelVariables>\n";
    let mut vr = 0usize;
    let mut variable = |s: &mut String, name: &str, attributes: &str, description: &str, real: &str| {
        *s += &format!("    <ScalarVariable name=\"{}\" valueReference=\"{vr}\" {attributes} description=\"{}\">\n      <Real {real}/>\n    </ScalarVariable>\n", escaped(name), escaped(description));
        vr += 1;
    };
    for j in 0..m {
        let real = format!("start=\"0\"{}", unit_attribute(export.input_units.get(j)));
        variable(&mut s, &export.inputs[j], &format!("causality=\"input\" variability=\"{variability}\""), &format!("input {} (a change from the reference)", j + 1), &real);
    }
    for i in 0..p {
        variable(&mut s, &export.outputs[i], &format!("causality=\"output\" variability=\"{variability}\""), &format!("output {} (a change from the reference)", i + 1), &unit_attribute(export.output_units.get(i)));
    }
    for k in 0..n {
        let name = export.states.get(k).cloned().unwrap_or_else(|| format!("x{}", k + 1));
        // A state's "unit" is what it measures (a modal coordinate and its scaling), said in
        // its description rather than as a unit.
        let description = match export.state_units.get(k).filter(|u| !u.trim().is_empty()) {
            Some(what) => format!("state {}: {what}", k + 1),
            None => format!("state {}", k + 1),
        };
        variable(&mut s, &name, &format!("causality=\"local\" variability=\"{state_variability}\" initial=\"exact\""), &description, "start=\"0\"");
    }
    if !discrete {
        for k in 0..n {
            let name = format!("der({})", export.states.get(k).cloned().unwrap_or_else(|| format!("x{}", k + 1)));
            variable(&mut s, &name, "causality=\"local\" variability=\"continuous\" initial=\"calculated\"", &format!("time derivative of state {}", k + 1), &format!("derivative=\"{}\"", m + p + k + 1));
        }
    }
    s += "  </ModelVariables>\n  <ModelStructure>\n";
    let unknowns = |from: usize, count: usize| (from..from + count).map(|i| format!("      <Unknown index=\"{}\"/>\n", i + 1)).collect::<String>();
    if p > 0 {
        s += &format!("    <Outputs>\n{}    </Outputs>\n", unknowns(m, p));
    }
    if !discrete && n > 0 {
        s += &format!("    <Derivatives>\n{}    </Derivatives>\n", unknowns(m + p + n, n));
    }
    if p > 0 || (!discrete && n > 0) {
        let derivatives = if discrete { String::new() } else { unknowns(m + p + n, n) };
        s += &format!("    <InitialUnknowns>\n{}{derivatives}    </InitialUnknowns>\n", unknowns(m, p));
    }
    s += "  </ModelStructure>\n</fmiModelDescription>\n";
    s
}
