//! What the importer needs from `modelDescription.xml` (FMI 2.0 or 3.0): the identifier, the GUID or
//! instantiation token, whether Model Exchange is offered, and each variable's value reference and type
//! (FMI 3.0's Float64 and Int32 read as Real and Integer). A plain scan of the attributes: the file is
//! ours and regular, and the check must not depend on the crate it checks.

use std::collections::HashMap;

pub struct ModelDescription {
    /// FMI 3.0 (else 2.0).
    pub fmi3: bool,
    pub model_identifier: String,
    /// The GUID (FMI 2.0) or the instantiationToken (FMI 3.0).
    pub guid: String,
    pub model_exchange: bool,
    pub states: usize,
    pub event_indicators: usize,
    /// name -> (value reference, type: Real, Integer, Boolean or String)
    pub variables: HashMap<String, (u32, String)>,
}

fn attribute(tag: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let end = tag[start..].find('"')? + start;
    Some(tag[start..end].replace("&lt;", "<").replace("&gt;", ">").replace("&quot;", "\"").replace("&amp;", "&"))
}

impl ModelDescription {
    pub fn parse(xml: &str) -> Result<ModelDescription, String> {
        let root_start = xml.find("<fmiModelDescription").ok_or("no <fmiModelDescription>")?;
        let root = &xml[root_start..root_start + xml[root_start..].find('>').ok_or("unclosed root tag")?];
        let fmi3 = attribute(root, "fmiVersion").is_some_and(|v| v.starts_with('3'));
        if fmi3 {
            return ModelDescription::parse_fmi3(xml, root);
        }
        let guid = attribute(root, "guid").ok_or("no guid")?;
        let cs = xml.find("<CoSimulation").ok_or("no <CoSimulation>")?;
        let cs_tag = &xml[cs..cs + xml[cs..].find('>').unwrap_or(0)];
        let model_identifier = attribute(cs_tag, "modelIdentifier").ok_or("no modelIdentifier")?;
        let number = |name: &str| attribute(root, name).and_then(|v| v.parse().ok()).unwrap_or(0);
        let mut variables = HashMap::new();
        let mut rest = xml;
        while let Some(at) = rest.find("<ScalarVariable") {
            let block_end = rest[at..]
                .find("</ScalarVariable>")
                .map(|e| at + e)
                .or_else(|| rest[at..].find("/>").map(|e| at + e))
                .ok_or("unclosed ScalarVariable")?;
            let block = &rest[at..block_end];
            let tag = &block[..block.find('>').unwrap_or(block.len())];
            let name = attribute(tag, "name").ok_or("a variable without a name")?;
            let vr = attribute(tag, "valueReference").and_then(|v| v.parse().ok()).ok_or(format!("{name}: no valueReference"))?;
            let ty = ["Real", "Integer", "Boolean", "String", "Enumeration"]
                .iter()
                .find(|t| block.contains(&format!("<{t}")))
                .ok_or(format!("{name}: no type"))?;
            variables.insert(name, (vr, ty.to_string()));
            rest = &rest[block_end..];
        }
        Ok(ModelDescription {
            fmi3: false,
            model_identifier,
            guid,
            model_exchange: xml.contains("<ModelExchange"),
            states: xml.find("<Derivatives>").map_or(0, |d| xml[d..d + xml[d..].find("</Derivatives>").unwrap_or(0)].matches("<Unknown").count()),
            event_indicators: number("numberOfEventIndicators"),
            variables,
        })
    }

    /// FMI 3.0: typed elements in ModelVariables, unknowns by value reference in ModelStructure.
    fn parse_fmi3(xml: &str, root: &str) -> Result<ModelDescription, String> {
        let guid = attribute(root, "instantiationToken").ok_or("no instantiationToken")?;
        let cs = xml.find("<CoSimulation").ok_or("no <CoSimulation>")?;
        let cs_tag = &xml[cs..cs + xml[cs..].find('>').unwrap_or(0)];
        let model_identifier = attribute(cs_tag, "modelIdentifier").ok_or("no modelIdentifier")?;
        let start = xml.find("<ModelVariables>").ok_or("no <ModelVariables>")?;
        let end = xml.find("</ModelVariables>").ok_or("unclosed <ModelVariables>")?;
        let mut variables = HashMap::new();
        for (fmi3_type, ty) in [("Float64", "Real"), ("Int32", "Integer"), ("Boolean", "Boolean"), ("String", "String")] {
            let open = format!("<{fmi3_type} ");
            for (at, _) in xml[start..end].match_indices(&open) {
                let tag = &xml[start + at..start + at + xml[start + at..].find('>').ok_or("unclosed variable")?];
                let name = attribute(tag, "name").ok_or("a variable without a name")?;
                let vr = attribute(tag, "valueReference").and_then(|v| v.parse().ok()).ok_or(format!("{name}: no valueReference"))?;
                variables.insert(name, (vr, ty.to_string()));
            }
        }
        Ok(ModelDescription {
            fmi3: true,
            model_identifier,
            guid,
            model_exchange: xml.contains("<ModelExchange"),
            states: xml.matches("<ContinuousStateDerivative ").count(),
            event_indicators: xml.matches("<EventIndicator ").count(),
            variables,
        })
    }

    pub fn vr(&self, name: &str) -> Result<u32, String> {
        self.variables.get(name).map(|v| v.0).ok_or_else(|| format!("{} has no variable `{name}`", self.model_identifier))
    }
}
